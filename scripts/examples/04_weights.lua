-- Tutorial 04: weights, load capacity and force flow (docs/guide/04_weights.md).
-- usage: ashlar scripts/examples/04_weights.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

-- Load capacity: how many times its own weight each voussoir can carry.
local arch = models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 }
local cap = ashlar.load_capacity(arch, { friction = math.huge })
local crown = 16                     -- the middle voussoir of 31 (the supports come after)
print(string.format("crown: %.2f x its weight, its neighbours %.2f and %.2f",
                    cap[crown].max, cap[crown - 1].max, cap[crown + 1].max))
local unbounded = 0
for i = 1, #arch do if cap[i] and cap[i].max == math.huge then unbounded = unbounded + 1 end end
print("voussoirs that can carry any load:", unbounded)
local shown = {}
for i = 1, #arch do shown[i] = cap[i] and math.min(cap[i].max, 5) or 0 end
ashlar.draw(arch, out .. "/04_arch_capacity.svg",
            { color = { values = shown, map = "viridis", range = { 0, 5 } }, title = "load capacity (x own weight, 5 and more yellow)" })
ashlar.legend(out .. "/04_capacity_legend.svg", { map = "viridis", range = { 0, 5 }, label = "x own weight" })

-- The blocks asked alone (option blocks): the same bounds, no entry for the others.
local asked = ashlar.load_capacity(arch, { friction = math.huge, blocks = { crown - 1, crown, crown + 1 } })
print(string.format("asked alone: crown %.2f, voussoir 1 %s", asked[crown].max, tostring(asked[1])))

-- Necessary weights: three stacked blocks, the middle one overhanging
-- its support by 0.1 m and keeping its weight.
local stack = ashlar.structure()
stack:add(ashlar.box{ size = { 4, 2, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "ground" })
stack:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.25 } }, { name = "bottom" })
stack:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.6, 0, 0.75 } }, { name = "middle" })
stack:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.2, 0, 1.25 } }, { name = "top" })
local w = ashlar.necessary_weights(stack, "middle")
print(string.format("least weights: bottom %.3f, top %.3f (x the middle block's)", w[2] / w[3], w[4] / w[3]))

-- Force flow: where the beam of an H frame sends its weight.
local flow = ashlar.trace_loads(models.h_frame{}, "beam", { traces = 200, seed = 1 })
local left, right = flow.shares[1].share, flow.shares[2].share   -- one share per post
print(string.format("beam weight to the two posts: %.3f / %.3f, lost %d", left, right, flow.lost))

assert(unbounded == 6, "three voussoirs by each support are unbounded")
assert(math.abs(cap[crown].max - 2.28) < 0.01 and math.abs(cap[crown - 1].max - 2.18) < 0.01, "crown 2.28, neighbours 2.18")
for _, i in ipairs{ crown - 1, crown, crown + 1 } do
  assert(math.abs(asked[i].max - cap[i].max) <= 1e-9 * cap[i].max, "the blocks asked have the whole run's bounds")
end
assert(asked[1] == nil, "a block not asked has no entry")
assert(w.stable and w[4] / w[3] >= 1 / 3 * (1 - 1e-6) and w[4] / w[3] < 0.34, "the top holds the middle down: >= 1/3")
assert(w[2] / w[3] < 1e-6, "the bottom needs no weight")
assert(#flow.shares == 2 and math.abs(left - 0.495) < 1e-9 and math.abs(right - 0.505) < 1e-9, "the beam splits its weight equally")
