-- ashlar.simulate (rigid-block dynamics) as a user calls it: the cases
-- where rigid-block equilibrium is wrong, a ground motion, the Simulation's
-- fields and methods, exports, compare_methods' dynamic verdict, the
-- interrupt and the errors. The arches: simulate_arch_spec.lua.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local cases = dofile("../../scripts/kinematic_cases.lua")
-- Newmark's rigid block sliding on a shaken base, in closed form.
local sliding = dofile("../../scripts/sliding_block.lua")

describe("ashlar.simulate", function()
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

  it("tips a leaning block off a pedestal's edge without its corner sinking into the pedestal", function()
    -- A 0.1 x 0.4 x 1 m block leaning 30 or 45 degrees past a pedestal's
    -- edge, its lower corner on the top face 1.5 or 2 cm from the edge (the
    -- search distance is 2.2 cm). The corner must keep to the top face while
    -- the block turns over the edge; taken against the side face (turned
    -- more towards the block's centroid, past the edge), it sank 4.6 and 6.2
    -- mm into the pedestal.
    for _, case in ipairs{ { 30, 0.015 }, { 45, 0.02 } } do
      local s = ashlar.structure()
      s:add(ashlar.box{ size = {1, 1, 1}, center = {-0.5, 0, -0.5} }, { support = true })
      s:add(ashlar.box{ size = {0.1, 0.4, 1}, center = {-0.05, 0, 0.5} }
        :rotated({0, 1, 0}, math.rad(case[1]), {0, 0, 0}):translated({-case[2], 0, 0}))
      local sim = ashlar.simulate(s, { duration = 0.4, friction = 0.7, record_every = 1 })
      local deepest = 0  -- how far a corner went inside the pedestal (x < 0, z < 0)
      for k = 1, sim.frames do
        for _, v in ipairs(sim:structure(k):block(2):vertices()) do
          deepest = math.max(deepest, math.min(-v[1], -v[3]))
        end
      end
      print(("leaning %d degrees, corner %.3f m from the edge: deepest into the pedestal %.3g m"):format(case[1],
        case[2], deepest))
      assert.is_true(sim.moved)
      assert.is_true(deepest < 1e-4, tostring(deepest))
    end
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

  it("solves every step of a tipping stack, or says how far it is from solved and where", function()
    local s = cases.stack(1.2)
    local sim = ashlar.simulate(s, { duration = 0.2 })
    assert.equal(0, sim.unconverged_steps)
    -- Solved: every step's residual within the tolerance, 1e-4 g h.
    assert.is_true(sim.max_residual <= 1e-4 * 9.81 * 1e-3)
    -- Held to 1e-12 g h with one sweep a step, steps are cut short: the
    -- largest residual is reported with its step and contact.
    -- A solve that stops near its tolerance (within twice it) is taken
    -- again in halves; these are far from it, and none is split.
    local cut = ashlar.simulate(s, { duration = 0.01, max_sweeps = 1, tolerance = 1e-12 })
    assert.is_true(cut.unconverged_steps > 0)
    assert.equal(0, cut.split_steps)
    assert.is_true(cut.max_residual > 1e-12 * 9.81 * 1e-3)
    assert.is_true(cut.max_residual_time > 0 and cut.max_residual_time <= 0.01 + 1e-12)
    local a, b = cut.max_residual_blocks[1], cut.max_residual_blocks[2]
    assert.is_true(a >= 1 and a <= #s and b >= 1 and b <= #s and a ~= b)
    -- A block falling freely has no contact: no residual, nowhere.
    local lone = ashlar.structure()
    lone:add(ashlar.box{ size = { 1, 1, 1 } })
    local fall = ashlar.simulate(lone, { duration = 0.01 })
    assert.equal(0, fall.max_residual)
    assert.is_nil(fall.max_residual_blocks)
    assert.is_nil(fall.max_residual_time)
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

  it("writes the HTML viewer's page with a player", function()
    local folder = support.temp_folder()
    local sim = ashlar.simulate(cases.stack(1.2), { duration = 0.3 })
    sim:export(folder .. "/run.html", { fps = 30, title = "a run", opacity = 0.8 })
    sim:export(folder .. "/run.page", { format = "html", color = { values = { 1, 2, 3 }, map = "viridis" },
                                        legend = "height (m)", edges = false })
    for _, name in ipairs{ "run.html", "run.page" } do
      local scene = support.read_file(folder .. "/" .. name)
        :match('<script type="application/json" id="ashlar%-scene">(.-)</script>')
      assert.truthy(scene:find('"animation":{"times":[0.0,', 1, true), name)
      assert.truthy(scene:find('"tracks":[{"objects":[1],', 1, true), name)
      assert.truthy(scene:find('"autoplay":true', 1, true), name)  -- plays as it opens
    end
    sim:export(folder .. "/paused.html", { autoplay = false })
    assert.truthy(support.read_file(folder .. "/paused.html"):find('"autoplay":false', 1, true))
    support.expect_error({ "autoplay: a still (frame = k) does not play" },
      function() sim:export(folder .. "/x.html", { frame = 1, autoplay = false }) end)
    support.expect_error({ 'autoplay: applies to an animated page (.html, or format = "html")' },
      function() sim:export(folder .. "/x.glb", { autoplay = false }) end)
    support.expect_error({ "forces: applies to a still (give frame = k)" },
      function() sim:export(folder .. "/x.html", { forces = true }) end)
    support.expect_error({ 'format: an animation is a .glb, or the HTML viewer with format = "html", got "compas"' },
      function() sim:export(folder .. "/x.json", { format = "compas" }) end)
    support.expect_error({ "title: applies to a still (give frame = k) or an animated page (.html" },
      function() sim:export(folder .. "/x.glb", { title = "run" }) end)
    support.expect_error({ "opacity: expected a number in [0, 1], got 2" },
      function() sim:export(folder .. "/x.html", { opacity = 2 }) end)
    support.expect_error({ "fps: expected a number >= 0, got -1" },
      function() sim:export(folder .. "/x.html", { fps = -1 }) end)
    support.remove_folder(folder)
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

  -- A running-bond wall of 0.4 x 0.2 x 0.2 m bricks, `length` x
  -- `height` m, friction 0.6, its ground shaken along it at a sin(w t)
  -- for `duration` s. Its load factor along its length is the friction
  -- (asserted): its base's sliding is its first mechanism, so it slides
  -- whole on its base as Newmark's block, every bed joint above the base at
  -- its friction limit without slipping: every free block at every frame
  -- within 2e-5 m of the closed form, every step converged.
  local function slides_as_newmarks_block(length, height, a, w, duration, free_blocks)
    local s = models.wall{ length = length, height = height, thickness = 0.2, brick = { 0.4, 0.2 } }
    s:set_planar(false)
    local mu = 0.6
    support.near(ashlar.load_factor(s, { friction = mu, direction = { -1, 0, 0 } }).factor, mu, 1e-9)
    local sim = ashlar.simulate(s, { duration = duration, friction = mu,
      ground_acceleration = function(t) return a * math.sin(w * t), 0, 0 end })
    assert.equal(0, sim.unconverged_steps)
    assert.is_true(sim.max_residual <= 1e-4 * 9.81 * 1e-3)
    local free = 0
    for i = 1, #s do
      if not s:is_support(i) then
        free = free + 1
        local path = sim:trajectory(i)
        for k, t in ipairs(path.times) do
          support.near(path.positions[k][1] - path.positions[1][1], sliding.displacement(a, w, mu, t), 2e-5)
        end
      end
    end
    assert.equal(free_blocks, free)
  end

  it("slides a wall on its base as Newmark's rigid block under a harmonic ground acceleration", function()
    -- Two courses, the ground at 1 g, 4 Hz: three slips in 0.4 s with
    -- sticks between (the closed form's slips start at 0.0256, 0.1506 and
    -- 0.2756 s); -0.0122439 m at 0.4 s. Every block within 7.5e-6 m at
    -- the 1 ms step (1.3e-6 at 0.5 ms): the time stepping's error.
    slides_as_newmarks_block(1.2, 0.4, 9.81, 2 * math.pi * 4, 0.4, 7)
  end)

  it("slides a five-course wall shaken at 1.5 g as Newmark's block, every step converged #unsanitized", function()
    -- 28 blocks (5 courses of 5 bricks), 1.5 g, 2 Hz: -0.1686666 m at 0.3
    -- s, every block within 1.14e-5 m. The sweeps alone stall on such
    -- steps (869 sweeps a step with the steps split); the interior-point
    -- method finishes them. Release suite only (47 s under the sanitizers):
    -- simulate_arch_spec's collapsing arches and unit.ContactInterior run
    -- that method under them.
    slides_as_newmarks_block(2, 1, 1.5 * 9.81, 2 * math.pi * 2, 0.3, 27)
  end)

  it("converges at every step on a wall shaken past a mechanism of its own #unsanitized", function()
    -- The 106-block wall of scripts/bench_simulate.lua's size (10 courses
    -- of 10 bricks), friction 0.6: load factor 0.524 along its length, a
    -- mechanism of many blocks sliding and rocking at once before its
    -- base slides. Shaken at 1.5 g, 2 Hz: without the interior-point
    -- method 9 of these 40 steps stopped at max_sweeps, up to 1.8e-4 m/s.
    -- Release suite only (34 s under the sanitizers), as the case above.
    local s = models.wall{ length = 4, height = 2, thickness = 0.2, brick = { 0.4, 0.2 } }
    s:set_planar(false)
    local a, w, mu = 1.5 * 9.81, 2 * math.pi * 2, 0.6
    local factor = ashlar.load_factor(s, { friction = mu, direction = { -1, 0, 0 } }).factor
    support.near(factor, 0.5238, 1e-3)
    local sim = ashlar.simulate(s, { duration = 0.04, friction = mu,
      ground_acceleration = function(t) return a * math.sin(w * t), 0, 0 end })
    print(("106-block wall, 1.5 g: %d steps, %d unconverged, %d split, %.1f sweeps a step, %.2f s"):format(sim.steps,
      sim.unconverged_steps, sim.split_steps, sim.sweeps / sim.steps, sim.seconds))
    assert.equal(40, sim.steps)
    assert.equal(0, sim.unconverged_steps)
    assert.is_true(sim.max_residual <= 1e-4 * 9.81 * 1e-3)
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

  it("finishes with a structure that its ground_acceleration closes", function()
    local s = cases.wedge()
    local sim = ashlar.simulate(s, { duration = 0.01, ground_acceleration = function(t)
      getmetatable(s).__close(s)
      return 0, 0, 0
    end })
    assert.equal(10, sim.steps)
    assert.is_false(sim.moved)
    assert.equal("Structure (closed)", tostring(s))
  end)

  it("splits a large solve over threads: the same numbers in every run, and within the tolerance of one thread's", function()
    -- A wall of 206 blocks (2,300 contact points, over the 2,000 from
    -- which a solve is split) shaken at 0.3 g, 2 Hz, friction 0.6: nothing
    -- may move (0.3 g is below the friction limit, 0.6 g, and a brick's
    -- uplift threshold, 0.24 / 0.07 g = 3.4 g), so each run's displacement
    -- is its error. Each step's solve leaves the
    -- velocities within tolerance x g x step = 1e-6 m/s of the laws, so
    -- over 10 steps of 1 ms two answers drift apart by at most about
    -- sum_k k x 2e-6 x 1e-3 = 1.1e-7 m.
    local s = models.wall{ length = 20 * 0.24, height = 10 * 0.07, brick = { 0.24, 0.07 } }
    local function run(threads)
      return ashlar.simulate(s, { duration = 0.01, friction = 0.6, threads = threads, record_every = 1,
                                  ground_acceleration = function(t) return 0.3 * 9.81 * math.sin(4 * math.pi * t), 0, 0 end })
    end
    local split, again, one = run(2), run(2), run(1)
    assert.is_true(split.max_active_contacts > 2000)
    assert.equal(0, split.unconverged_steps)
    assert.equal(split.sweeps, again.sweeps)
    for i = 1, #s do
      assert.equal(split.displacements[i], again.displacements[i])  -- to the bit
      local a, b = split:trajectory(i), again:trajectory(i)
      for f = 1, #a.positions do
        for k = 1, 3 do
          assert.equal(a.positions[f][k], b.positions[f][k])
          assert.equal(a.rotations[f][k], b.rotations[f][k])
        end
      end
      assert.is_true(math.abs(split.displacements[i] - one.displacements[i]) <= 1.1e-7)
    end
    assert.is_true(split.max_displacement < 1e-7 and one.max_displacement < 1e-7)
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
    support.expect_error({ "threads", "-1" }, function() ashlar.simulate(s, { threads = -1 }) end)
    support.expect_error({ "ground_acceleration: expected a GroundMotion (ashlar.ground_motion) or a function", "got number" },
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
