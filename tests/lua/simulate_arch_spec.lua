-- ashlar.simulate on semicircular arches, against the other analyses: above
-- its minimum thickness an arch stays put, below it collapses on the hinges
-- where the equilibrium's thrust line touches the joints at the minimum;
-- pushed sideways it stands below its load factor and fails above it on the
-- load factor's mechanism.
local ashlar = require "ashlar"
local models = require "ashlar.models"

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

describe("ashlar.simulate on arches", function()
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
    assert.equal(0, sim.unconverged_steps)
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
    local sim = ashlar.simulate(s, { duration = 0.5, friction = 0.7, record_every = 1 })
    assert.is_true(sim.moved)
    -- Every step solved outright: the hinges carry one normal each, no wedge
    -- of two (with the wedges, a step at 0.496 s stalled at 1.6 times the
    -- tolerance and was taken in halves).
    assert.equal(0, sim.unconverged_steps)
    assert.equal(0, sim.split_steps)
    assert.is_true(sim.max_residual <= 1e-4 * 9.81 * 1e-3)
    -- With 20 sweeps a solve, a step that stalls within twice the tolerance
    -- is taken in halves, and they converge.
    local short = ashlar.simulate(s, { duration = 0.5, friction = 0.7, max_sweeps = 20 })
    print(("thin arch, 20 sweeps a solve: %d steps split, %d unconverged"):format(short.split_steps,
      short.unconverged_steps))
    assert.is_true(short.split_steps >= 1)
    assert.equal(0, short.unconverged_steps)
    local got = simulated_hinges(s, sim, 1e-3)
    print("thin arch hinges: thrust line at the edges (t/R 0.1071) " .. expected .. "; simulation (t/R 0.09) " .. got)
    assert.equal("1-17 13-14 16-18 3-4 8-9", expected)  -- springings, haunches, crown
    assert.equal(expected, got)
  end)

  it("stands below the load factor and fails above it at the load-factor hinges", function()
    local s = arch(0.75)  -- t/R = 0.15
    local f = ashlar.load_factor(s, { friction = 0.7 })
    local function pushed(fraction)
      return ashlar.simulate(s, { duration = 0.5, friction = 0.7, record_every = 1,
                                  gravity = { fraction * f.factor * 9.81, 0, -9.81 } })
    end
    local below, above = pushed(0.9), pushed(1.1)
    local expected, got = limit_hinges(f.limit), simulated_hinges(s, above, 1e-3)
    print(("load factor %.4f: at 0.9 of it the arch moves %.3g m, at 1.1 %.3g m; hinges: load factor %s; simulation %s; "
      .. "unconverged steps %d and %d"):format(f.factor, below.max_displacement, above.max_displacement, expected, got,
      below.unconverged_steps, above.unconverged_steps))
    assert.is_false(below.moved)
    assert.is_true(above.moved)
    assert.equal(expected, got)
    -- Every step of the arch that stands solved (the sweeps alone stalled
    -- on 2 of its 500).
    assert.equal(0, below.unconverged_steps)
  end)

  it("solves every step of a collapse up to its first block's fall", function()
    -- Semicircular arches of 18, 22 and 24 voussoirs, t/R 0.09, collapsing
    -- from rest, for 0.6 s: up to the first fall and a little past it.
    -- Their hinges opened into wedges of two normals, and their corners on
    -- the next block's edge pressed the face beside the joint: 26 and 19
    -- steps of the 18 and 22 voussoirs stopped above the tolerance, up to
    -- 2.3e-4 m/s (convergence_runs.lua, docs/performance.md).
    for _, voussoirs in ipairs{ 18, 22, 24 } do
      local s = models.arch{ radius = 5, thickness = 0.45, voussoirs = voussoirs }
      local sim = ashlar.simulate(s, { duration = 0.6, friction = 0.7, record_every = 10 })
      local fell = sim:summary().collapse_time
      print(("%d voussoirs: first fall at %s s; %d of %d steps unconverged, largest residual %.3g m/s at %s s")
        :format(voussoirs, tostring(fell), sim.unconverged_steps, sim.steps, sim.max_residual,
                tostring(sim.max_residual_time)))
      assert.is_true(fell ~= nil and fell <= 0.6)  -- it collapses within the run
      assert.equal(0, sim.unconverged_steps)
      assert.is_true(sim.max_residual <= 1e-4 * 9.81 * 1e-3)
    end
  end)

end)
