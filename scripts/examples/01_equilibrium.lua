-- Tutorial 01: equilibrium and thrust lines (docs/guide/01_equilibrium.md).
-- usage: ashlar scripts/examples/01_equilibrium.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

-- A semicircular arch: centreline radius 5 m, 31 voussoirs, t/R = 0.12.
local arch = models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 }
local r = ashlar.analyze(arch, { friction = 0.7 })
print(string.format("t = 0.60 m: stable %s, infeasibility %.3g, %d interfaces",
                    tostring(r.stable), r.infeasibility, #r.interfaces))
local line = r:thrust_line()
print(string.format("thrust line: %d centres of pressure", #line))
ashlar.draw(arch, out .. "/01_arch_thrust.svg", { result = r, title = "t/R = 0.12: stable" })

-- The same arch, thinner than its minimum (about 0.107 R): no thrust line
-- fits, the best equilibrium needs tension.
local thin = models.arch{ radius = 5, thickness = 0.45, voussoirs = 31 }
local q = ashlar.analyze(thin, { friction = 0.7 })
print(string.format("t = 0.45 m: stable %s, infeasibility %.4f", tostring(q.stable), q.infeasibility))
ashlar.draw(thin, out .. "/01_arch_thin.svg", { result = q, forces = true, title = "t/R = 0.09: needs tension" })

-- Its minimum thickness, which the chapter quotes as about 0.107 R.
local g = ashlar.geometric_factor(function(t) return models.arch{ radius = 5, thickness = t, voussoirs = 31 } end,
                                  0.6, { friction = math.huge })
print(string.format("minimum thickness t/R = %.4f", g.minimum / 5))

assert(math.abs(g.minimum / 5 - 0.1071) < 1e-4, "minimum t/R of 31 voussoirs")
assert(r.stable and r.infeasibility == 0, "the 0.6 m arch stands")
assert(#r.interfaces == 32 and #line == 32, "one centre of pressure per joint")
assert(not q.stable and math.abs(q.infeasibility - 0.2913) < 5e-4, "the 0.45 m arch needs tension")
