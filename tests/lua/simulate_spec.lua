-- ashlar.simulate (rigid-block dynamics) as a user calls it: the arch checks
-- against the minimum thickness and against the equilibrium and load-factor
-- analyses' hinges, the cases where rigid-block equilibrium is wrong, the
-- Simulation's fields and methods, exports, compare_methods' dynamic
-- verdict, and the errors.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local cases = dofile("../../scripts/kinematic_cases.lua")

-- 16 polyhedral voussoirs, radius 5: the minimum thickness is 0.10708 R.
local function arch(thickness)
  return models.arch{ radius = 5, thickness = thickness, voussoirs = 16, depth = 1 }
end

-- The joints (a, b), a < b, of `s` where the rotation of b relative to a
-- (about y, the arch's axis) is at least a fifth of the largest: the hinges
-- of the motion that `rotation(i)` gives (a vector, zero for supports).
local function hinges(s, rotation)
  local turns, largest = {}, 0
  for _, joint in ipairs(s:interfaces()) do
    local turn = math.abs(rotation(joint.b)[2] - rotation(joint.a)[2])
    turns[#turns + 1] = { joint.a, joint.b, turn }
    largest = math.max(largest, turn)
  end
  local out = {}
  for _, t in ipairs(turns) do
    if t[3] >= 0.2 * largest then out[#out + 1] = t[1] .. "-" .. t[2] end
  end
  table.sort(out)
  return table.concat(out, " ")
end

-- The hinges of a limit (ashlar.analyze's or ashlar.load_factor's).
local function limit_hinges(limit)
  local out = {}
  for _, joint in ipairs(limit) do
    if joint.mode == "hinge" or joint.mode == "hinge_sliding" then out[#out + 1] = joint.a .. "-" .. joint.b end
  end
  table.sort(out)
  return table.concat(out, " ")
end

-- The hinges the simulation shows when its largest displacement first
-- passes `early` (m): rotations relative to the start.
local function simulated_hinges(s, sim, early)
  local trajectories = {}
  for i = 1, #s do trajectories[i] = sim:trajectory(i) end
  for k = 1, sim.frames do
    for i = 1, #s do
      local p, p0 = trajectories[i].positions[k], trajectories[i].positions[1]
      if math.sqrt((p[1] - p0[1]) ^ 2 + (p[2] - p0[2]) ^ 2 + (p[3] - p0[3]) ^ 2) > early then
        return hinges(s, function(j) return trajectories[j].rotations[k] end)
      end
    end
  end
end

describe("ashlar.simulate", function()
  it("keeps a semicircular arch above its minimum thickness still for 2 s", function()
    local s = arch(0.6)  -- t/R = 0.12 > 0.107
    local sim = ashlar.simulate(s, { duration = 2, friction = 0.7 })
    local span = 10 + 0.6
    print(("arch t/R 0.12: largest displacement %.3g m = %.3g of the span over 2 s"):format(
      sim.max_displacement, sim.max_displacement / span))
    assert.is_true(sim.max_displacement < 1e-6 * span)
    assert.is_false(sim.moved)
    assert.is_true(sim.settled)
    assert.equal("completed", sim.status)
    assert.equal(2000, sim.steps)
  end)

  it("collapses a thinner arch, with the hinges of the equilibrium at the minimum thickness", function()
    -- At t/R = 0.1071 (the minimum, 0.10708, for 16 voussoirs) the
    -- equilibrium's thrust line touches the joint edges where the collapse
    -- mechanism hinges: its centre of pressure within 1 % of the half
    -- thickness from an edge.
    local t = 0.1071 * 5
    local at_minimum = arch(t)
    local r = ashlar.analyze(at_minimum, { friction = 0.7 })
    assert.is_true(r.stable)
    local edges, joints = {}, at_minimum:interfaces()
    for k, f in ipairs(r.interfaces) do
      local c, p = joints[k].center, f.center_of_pressure
      local e = math.sqrt((p[1] - c[1]) ^ 2 + (p[2] - c[2]) ^ 2 + (p[3] - c[3]) ^ 2)
      if e > 0.99 * t / 2 then edges[#edges + 1] = f.a .. "-" .. f.b end
    end
    table.sort(edges)
    local expected = table.concat(edges, " ")
    local s = arch(0.45)  -- t/R = 0.09 < 0.107
    assert.is_false(ashlar.analyze(s, { friction = 0.7 }).stable)
    local sim = ashlar.simulate(s, { duration = 1, friction = 0.7, record_every = 1 })
    assert.is_true(sim.moved)
    local got = simulated_hinges(s, sim, 1e-3)
    print("thin arch hinges: thrust line at the edges (t/R 0.1071) " .. expected .. "; simulation (t/R 0.09) " .. got)
    assert.equal("1-17 13-14 16-18 3-4 8-9", expected)  -- springings, haunches, crown
    assert.equal(expected, got)
  end)

  it("stands below the load factor and fails above it at the load-factor hinges", function()
    local s = arch(0.75)  -- t/R = 0.15
    local f = ashlar.load_factor(s, { friction = 0.7 })
    local function pushed(fraction)
      return ashlar.simulate(s, { duration = 1, friction = 0.7, record_every = 1,
                                  gravity = { fraction * f.factor * 9.81, 0, -9.81 } })
    end
    local below, above = pushed(0.9), pushed(1.1)
    local expected, got = limit_hinges(f.limit), simulated_hinges(s, above, 1e-3)
    print(("load factor %.4f: at 0.9 of it the arch moves %.3g m, at 1.1 %.3g m; hinges: load factor %s; simulation %s")
      :format(f.factor, below.max_displacement, above.max_displacement, expected, got))
    assert.is_false(below.moved)
    assert.is_true(above.moved)
    assert.equal(expected, got)
  end)

  it("lets a block clamped between two walls fall freely, whatever the friction", function()
    for _, mu in ipairs{ 0.3, 0.9, math.huge } do
      local s = cases.clamped()
      assert.is_true(ashlar.analyze(s, { friction = mu }).stable)  -- equilibrium is wrong here
      local sim = ashlar.simulate(s, { duration = 0.5, friction = mu })
      local path = sim:trajectory(3)
      local drop = path.positions[1][3] - path.positions[#path.positions][3]
      support.near(drop, 0.5 * 9.81 * 0.25, 1e-6, "mu " .. mu)
      assert.is_true(sim.moved)
    end
  end)

  it("keeps a wedge seated in a V at rest", function()
    local sim = ashlar.simulate(cases.wedge(), { duration = 0.5, friction = 0.3 })
    assert.is_false(sim.moved)
    assert.is_true(sim.max_displacement < 1e-7)
  end)

  it("gives fields, trajectories and a printable Simulation", function()
    local s = cases.stack(1.2)  -- tips
    local sim = ashlar.simulate(s, { duration = 0.2, step = 0.002, record_every = 10 })
    assert.equal(100, sim.steps)
    assert.equal(11, sim.frames)
    assert.near(0.2, sim.time, 1e-12)
    assert.is_true(sim.seconds >= 0)
    assert.is_true(sim.moved)
    assert.is_number(sim.max_displacement_block)
    assert.equal(#s, #sim.displacements)
    assert.equal(0, sim.displacements[1])  -- the support
    local path = sim:trajectory(2)
    assert.equal(11, #path.times)
    assert.near(0.02, path.times[2], 1e-12)
    assert.equal(3, #path.positions[1])
    assert.equal(3, #path.rotations[1])
    assert.same(path.positions, sim:trajectory("block 2").positions)
    assert.matches("^Simulation %(completed, 100 steps", tostring(sim))
    -- The structure at a frame: blocks where the run put them.
    local last = sim:structure(sim.frames)
    assert.equal(#s, #last)
    local c, p = last:block(3):centroid(), sim:trajectory(3).positions[sim.frames]
    for k = 1, 3 do assert.near(p[k], c[k], 1e-9) end
    support.expect_error({ "frame: expected a frame number from 1 to 11, got 12" }, function() sim:structure(12) end)
    getmetatable(sim).__close(sim)
    assert.equal("Simulation (closed)", tostring(sim))
    support.expect_error({ "closed Simulation" }, function() return sim.moved end)
  end)

  it("writes an animated .glb and a still of any frame", function()
    local folder = os.tmpname()
    os.remove(folder)
    os.execute("mkdir -p " .. support.quote(folder))
    local s = cases.stack(1.2)
    local sim = ashlar.simulate(s, { duration = 0.3 })
    sim:export(folder .. "/run.glb", { fps = 30 })
    sim:export(folder .. "/last.obj", { frame = sim.frames })
    sim:export(folder .. "/first.glb", { frame = 1, edges = true })
    for _, name in ipairs{ "run.glb", "last.obj", "first.glb" } do
      local f = assert(io.open(folder .. "/" .. name, "rb"))
      assert.is_true(#f:read("a") > 100, name)
      f:close()
    end
    local f = assert(io.open(folder .. "/run.glb", "rb"))
    local glb = f:read("a")
    f:close()
    assert.equal("glTF", glb:sub(1, 4))
    assert.truthy(glb:find('"animations"', 1, true))
    support.expect_error({ "frame: expected a frame number from 1 to " .. sim.frames .. ", got 0" },
      function() sim:export(folder .. "/x.glb", { frame = 0 }) end)
    support.expect_error({ "an animation is written as .glb" }, function() sim:export(folder .. "/x.obj") end)
    support.expect_error({ "edges: applies to a still" }, function() sim:export(folder .. "/x.glb", { edges = true }) end)
    os.execute("rm -rf " .. support.quote(folder))
  end)

  it("follows a prescribed ground acceleration", function()
    -- A block on a base accelerated at 0.1 g along x, friction 0.05: it
    -- slides back relative to the base at (0.1 - 0.05) g.
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 6, 2, 0.2 }, center = { 0, 0, -0.1 } }, { support = true })
    s:add(ashlar.box{ size = { 0.5, 0.5, 0.3 }, center = { 0, 0, 0.15 } })
    local sim = ashlar.simulate(s, { duration = 1, friction = 0.05,
                                     ground_acceleration = function(t) return 0.1 * 9.81, 0, 0 end })
    local path = sim:trajectory(2)
    support.near(path.positions[#path.positions][1] - path.positions[1][1], -0.5 * 0.05 * 9.81, 1e-3 * 0.245)
  end)

  it("adds the dynamic verdict to compare_methods when asked", function()
    local c = ashlar.compare_methods(cases.clamped(), { friction = 0.6, dynamics = { duration = 0.3 } })
    assert.is_true(c.equilibrium.stable)
    assert.is_false(c.kinematic.stable)
    assert.is_true(c.dynamic.moved)
    local w = ashlar.compare_methods(cases.wedge(), { friction = 0.6, dynamics = true })
    assert.is_false(w.dynamic.moved)
    assert.is_nil(ashlar.compare_methods(cases.wedge(), { friction = 0.6 }).dynamic)
  end)

  it("stops on an interrupt with what it computed and no verdict", function()
    local outcome = ashlar.sandbox{ source = [[
      local ashlar = require "ashlar"
      local s = ashlar.structure()
      s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 10 } })
      local sim = ashlar.simulate(s, { duration = 1e4, step = 1e-3 })
      return sim.status
    ]], time = 0.5 }
    assert.equal("time", outcome.status)
    assert.is_true(outcome.seconds < 5)  -- the run stopped at the deadline, not after 1e7 steps
  end)

  it("names the argument and the value it got in errors", function()
    local s = cases.wedge()
    support.expect_error({ "bad argument #2 to 'simulate'", "step" , "-1" },
      function() ashlar.simulate(s, { step = -1 }) end)
    support.expect_error({ "restitution must be in [0, 1], got 2" },
      function() ashlar.simulate(s, { restitution = 2 }) end)
    support.expect_error({ "friction: expected a number >= 0", "got -0.5" },
      function() ashlar.simulate(s, { friction = -0.5 }) end)
    support.expect_error({ "unknown", "durration" }, function() ashlar.simulate(s, { durration = 1 }) end)
    support.expect_error({ "ground_acceleration: expected a function", "got number" },
      function() ashlar.simulate(s, { ground_acceleration = 3 }) end)
    support.expect_error({ "ground_acceleration: the function must return three finite numbers", "result 2 is nil" },
      function() ashlar.simulate(s, { duration = 0.01, ground_acceleration = function(t) return 1 end }) end)
    support.expect_error({ "boom" },
      function() ashlar.simulate(s, { duration = 0.01, ground_acceleration = function(t) error("boom") end }) end)
    support.expect_error({ "Structure expected, got number" }, function() ashlar.simulate(3) end)
    local sim = ashlar.simulate(s, { duration = 0.01 })
    support.expect_error({ "block: index 9 is out of range" }, function() sim:trajectory(9) end)
  end)
end)
