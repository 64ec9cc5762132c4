-- Tutorial 02: when equilibrium is wrong: the kinematic method and the
-- dynamics (docs/guide/02_kinematic.md).
-- usage: ashlar scripts/examples/02_kinematic.lua [figure folder]
local ashlar = require "ashlar"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

-- A block set between two walls, with nothing under it.
local s = ashlar.structure()
s:add(ashlar.box{ size = { 1, 1, 2 }, center = { -0.5, 0, 1 } }, { support = true, name = "left wall" })
s:add(ashlar.box{ size = { 1, 1, 2 }, center = { 1.5, 0, 1 } }, { support = true, name = "right wall" })
s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.5, 0, 1.5 } }, { name = "block" })

local eq = ashlar.analyze(s, { friction = 0.6 })
local kin = ashlar.analyze(s, { friction = 0.6, method = "kinematic" })
print("equilibrium stable:", eq.stable)
print("kinematic stable:  ", kin.stable, kin.method, kin.status)
local m = kin.mechanism[3]
print(string.format("block 3 starts to move with vertical velocity %.3f", m.velocity[3]))
for _, joint in ipairs(kin.limit) do print("joint", joint.a, joint.b, joint.mode) end

-- What the equilibrium borrowed: each wall holds half the weight by
-- friction, on compression the kinematic method does not find.
local c = ashlar.compare_methods(s, { friction = 0.6 })
local weight = 9.81 * s:block(3):mass()
for _, b in ipairs(c.borrowed) do
  print(string.format("joint %d-%d: friction %.3f W, available %.3f W", b.a, b.b, b.friction / weight, b.available / weight))
  assert(math.abs(b.friction / weight - 0.5) < 1e-6 and b.available < 1e-2 * weight, "half the weight on each wall")
end
assert(#c.borrowed == 2)

-- The dynamics referee: a quarter of a second from rest.
local sim = ashlar.simulate(s, { duration = 0.25, friction = 0.6 })
local path = sim:trajectory(3)
local drop = path.positions[1][3] - path.positions[#path.positions][3]
print(string.format("after %.2f s the block has fallen %.7f m (1/2 g t^2 = %.7f m)",
                    sim.time, drop, 0.5 * 9.81 * 0.25 ^ 2))
ashlar.draw(sim:structure(sim.frames), out .. "/02_clamped_fallen.svg",
            { title = "the clamped block after 0.25 s" })

assert(eq.stable, "equilibrium finds friction from normal forces nothing presses in")
assert(not kin.stable and kin.status == "converged", "the kinematic method lets it fall")
assert(math.abs(m.velocity[3] + 1) < 1e-6, "straight down")
assert(#kin.limit == 2 and kin.limit[1].mode == "sliding" and kin.limit[2].mode == "sliding")
assert(sim.moved, "the dynamics lets it fall")
assert(math.abs(drop - 0.3065625) < 1e-6, "free fall: 1/2 g t^2")
