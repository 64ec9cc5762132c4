-- Tutorial 05: cables, structural gradients and optimisation
-- (docs/guide/05_optimise.md).
-- usage: ashlar scripts/examples/05_optimise.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

-- A beam on a post at its left end, held at its right end by a cable to a mast.
local s = ashlar.structure()
s:add(ashlar.box{ size = { 0.4, 1, 3 }, center = { 0, 0, 1.5 } }, { support = true, name = "post" })
s:add(ashlar.box{ size = { 0.4, 1, 6 }, center = { 4.2, 0, 3 } }, { support = true, name = "mast" })
s:add(ashlar.box{ size = { 3.6, 1, 0.3 }, center = { 1.8, 0, 3.15 } }, { name = "beam" })
local without = ashlar.analyze(s, { friction = 0.7 })
s:add_cable{ from = { block = "beam", point = { 3.5, 0, 3.3 } }, to = { block = "mast", point = { 4, 0, 5.5 } },
             mass_per_length = 5 }
local with = ashlar.analyze(s, { friction = 0.7 })
print("beam without the cable: stable", without.stable, "with it:", with.stable)
print(string.format("cable tension %.0f N", with.cables[1].tension))

-- The structural gradient and an optimisation: an arch of 24 voussoirs at
-- 3/4 of its minimum thickness, mirror-symmetric moves, no sliding.
local arch = models.arch{ radius = 5, thickness = 0.4, voussoirs = 24 }
local options = { analysis = { friction = math.huge }, initial_step = 0.01, progress = false,
                  symmetry = { point = { 0, 0, 0 }, normal = { 1, 0, 0 } } }
local g = ashlar.gradient(arch, options.analysis)
local minimum = ashlar.geometric_factor(function(t) return models.arch{ radius = 5, thickness = t, voussoirs = 24 } end,
                                        0.6, options.analysis).minimum
print(string.format("minimum thickness %.3f m: 0.4 m is %.2f of it", minimum, 0.4 / minimum))
assert(math.abs(minimum - 0.535) < 1e-3, "minimum thickness of the 24-voussoir arch")
print(string.format("penalty %.4f before", ashlar.analyze(arch, options.analysis).penalty))
local rows = {}
for _, method in ipairs{ "gradient", "lbfgs" } do
  options.method = method
  local o = ashlar.optimize(arch, options)
  for _, h in ipairs(o.history) do
    rows[#rows + 1] = { iteration = h.iteration, infeasibility = h.infeasibility, method = method }
  end
  print(string.format("%-8s stable %s after %d iterations (%s)", method, tostring(o.stable),
                      o.history[#o.history].iteration, o.status))
  assert(o.stable, method .. " reaches a stable arch")
end
ashlar.chart{ path = out .. "/05_optimisation.svg", data = rows, x = "iteration", y = "infeasibility",
              series = "method", title = "Arch t/R = 0.08, 24 voussoirs" }

assert(not without.stable and with.stable, "the cable holds the beam")
assert(#g == #arch, "one gradient entry per block")
assert(math.abs(with.cables[1].tension - 13323) < 1, "cable tension")
