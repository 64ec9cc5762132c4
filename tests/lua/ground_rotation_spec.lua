-- ashlar.simulate's ground_rotation and ground_pivot (a turning support)
-- as a user calls them, against closed forms in the ground's frame: a
-- block on a slowly tilting support slides at the friction angle, a
-- slender one lifts off at atan(b / h), a block on a spinning support
-- slides outward once omega^2 r > mu g; a ground that does not turn
-- changes nothing; compare_methods' dynamics takes them too; bad options
-- are errors naming the option and the value.
local ashlar = require "ashlar"
local support = require "spec_support"

local g = 9.81

-- A support slab and one free block (size, centre), as a Structure.
local function block_on(slab, size, center)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = slab, center = { 0, 0, -0.1 } }, { support = true })
  s:add(ashlar.box{ size = size, center = center })
  return s
end

-- The first time in `times` at which measure(k) exceeds threshold.
local function first_above(times, threshold, measure)
  for k = 1, #times do
    if measure(k) > threshold then return times[k] end
  end
end

-- The root of an increasing f on [lo, hi] by bisection.
local function root(f, lo, hi)
  for _ = 1, 200 do
    local mid = 0.5 * (lo + hi)
    if f(mid) > 0 then hi = mid else lo = mid end
  end
  return 0.5 * (lo + hi)
end

local function norm(v) return math.sqrt(v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2) end

describe("ashlar.simulate with ground_rotation", function()
  it("slides a block off a slowly tilting support when tan(theta) reaches mu, and not before", function()
    -- Tilting about +y at 0.2 rad/s, mu 0.5: slip at t* = atan(mu) / rate
    -- = 2.318 s, then x'' = g (sin(rate t) - mu cos(rate t)) from rest; the
    -- frame's centrifugal force (4e-4 g here) moves t* by about 1 ms. Its
    -- travel is checked against the frame's equation along the slope with
    -- the centrifugal force and Coriolis' (which lifts the sliding block),
    -- centroid z_c = 0.1 m above the pivot, by RK4 from the slip:
    --   x'' = g sin(theta) + rate^2 x - mu (g cos(theta) - rate^2 z_c - 2 rate x')
    local rate, mu = 0.2, 0.5
    local s = block_on({ 4, 1, 0.2 }, { 0.4, 0.4, 0.2 }, { 0, 0, 0.1 })
    local sim = ashlar.simulate(s, { duration = 2.6, friction = mu, tolerance = 1e-8, record_every = 1,
      ground_rotation = function(t) return 0, rate * t, 0 end })
    local slip = math.atan(mu) / rate
    local function slid(t)
      local a, b = rate * slip, rate * t
      return g * ((math.sin(a) - math.sin(b)) / rate ^ 2 + mu * (math.cos(b) - math.cos(a)) / rate ^ 2 +
        (math.cos(a) + mu * math.sin(a)) * (t - slip) / rate)
    end
    local path = sim:trajectory(2)
    local function moved(k) return path.positions[k][1] - path.positions[1][1] end
    local before = 0
    for k = 1, #path.times do
      if path.times[k] <= slip - 0.025 then before = math.max(before, math.abs(moved(k))) end
    end
    assert.is_true(before < 1e-9, "moved " .. before .. " m below the friction angle")
    local threshold = 1e-5
    -- The first movement as the summary reports it (a vertex 10 um away).
    local first = sim:summary{ moved_fraction = threshold / math.sqrt(0.4 ^ 2 + 0.4 ^ 2 + 0.2 ^ 2) }.first_movement
    support.near(first, root(function(t) return slid(t) - threshold end, slip, slip + 1), 3e-3, "first movement")
    local function acceleration(t, x, v)
      return g * math.sin(rate * t) + rate ^ 2 * x - mu * (g * math.cos(rate * t) - rate ^ 2 * 0.1 - 2 * rate * v)
    end
    local t, x, v, dt = root(function(t) return acceleration(t, 0, 0) end, 0, 2 * slip), 0, 0, 1e-4
    while t < 2.6 do
      local h = math.min(dt, 2.6 - t)
      local a1 = acceleration(t, x, v)
      local a2 = acceleration(t + h / 2, x + h / 2 * v, v + h / 2 * a1)
      local a3 = acceleration(t + h / 2, x + h / 2 * (v + h / 2 * a1), v + h / 2 * a2)
      local a4 = acceleration(t + h, x + h * (v + h / 2 * a2), v + h * a3)
      x, v, t = x + h * v + h * h / 6 * (a1 + a2 + a3), v + h / 6 * (a1 + 2 * a2 + 2 * a3 + a4), t + h
    end
    support.near(moved(#path.times), x, 1e-3 * x, "slid by 2.6 s")
  end)

  it("lifts a slender block off a slowly tilting support when theta reaches atan(b / h), and not before", function()
    -- 0.1 m wide, 0.5 m tall, friction 0.8; tilting at 0.1 rad/s, it lifts
    -- at t* = atan(0.2) / 0.1 = 1.974 s; past it, rocking about its edge
    -- (linearised) turns it by phi = rate (sinh(p tau) / p - tau),
    -- p^2 = 3 g / (4 R), R the half-diagonal, tau = t - t*.
    local rate, b, h = 0.1, 0.1, 0.5
    local s = block_on({ 3, 1, 0.2 }, { b, 0.4, h }, { 0, 0, h / 2 })
    local sim = ashlar.simulate(s, { duration = 2.2, friction = 0.8, tolerance = 1e-8, record_every = 1,
      ground_rotation = function(t) return 0, rate * t, 0 end })
    local lift = math.atan(b / h) / rate
    local p = math.sqrt(3 * g / (4 * 0.5 * math.sqrt(b * b + h * h)))
    local path = sim:trajectory(2)
    local function turned(k) return norm(path.rotations[k]) end
    local before = 0
    for k = 1, #path.times do
      if path.times[k] <= lift - 0.05 then before = math.max(before, turned(k)) end
    end
    assert.is_true(before < 1e-8, "turned " .. before .. " rad before atan(b / h)")
    local threshold = 1e-4
    local expected = lift + root(function(tau) return rate * (math.sinh(p * tau) / p - tau) - threshold end, 0, 1)
    support.near(first_above(path.times, threshold, turned), expected, 5e-3, "lift-off")
  end)

  it("slides a block on a spinning support outward once omega^2 r exceeds mu g", function()
    -- Centroid 1 m from the axis, mu 0.2: omega_c = sqrt(mu g / r). Above
    -- it, x'' = omega^2 (r + x) - mu g radially (Coriolis' force turns the
    -- slide by about 0.05 rad: 0.1 % of x).
    local mu, r = 0.2, 1
    local critical = math.sqrt(mu * g / r)
    local function spin(omega, duration)
      local s = block_on({ 4, 4, 0.2 }, { 0.2, 0.2, 0.1 }, { r, 0, 0.05 })
      return ashlar.simulate(s, { duration = duration, friction = mu, tolerance = 1e-8,
        ground_rotation = function(t) return 0, 0, omega * t end })
    end
    local below = spin(0.95 * critical, 0.5)
    assert.is_false(below.moved)
    assert.is_true(below.max_displacement < 1e-9, "moved " .. below.max_displacement .. " m below omega_c")
    local omega = 1.05 * critical
    local path = spin(omega, 0.2):trajectory(2)
    local travel = { path.positions[#path.positions][1] - r, path.positions[#path.positions][2] }
    local expected = (omega ^ 2 * r - mu * g) / omega ^ 2 * (math.cosh(omega * 0.2) - 1)
    support.near(travel[1], expected, 0.01 * expected, "outward slide in 0.2 s")
    assert.is_true(math.abs(travel[2]) < 0.1 * travel[1])
  end)

  it("changes nothing, to the bit, when the ground does not turn", function()
    local s = block_on({ 3, 1, 0.2 }, { 0.3, 0.4, 1.2 }, { 0, 0, 0.6 })
    local function shake(t) return 0.5 * g * math.sin(4 * math.pi * t), 0, 0 end
    local still = ashlar.simulate(s, { duration = 0.3, friction = 0.8, ground_acceleration = shake })
    local turning = ashlar.simulate(s, { duration = 0.3, friction = 0.8, ground_acceleration = shake,
      ground_rotation = function() return 0, 0, 0 end, ground_pivot = { 2, -1, 3 } })
    assert.is_true(still.max_displacement > 1e-3)
    assert.same(still:trajectory(2), turning:trajectory(2))
  end)

  it("takes a GroundMotion as the rotation, its values in rad", function()
    -- A table in "m/s2" is read unscaled: about y, 0 at t = 0, 0.3 rad
    -- from 1 s (to 2 s, past the run and the step after it).
    local folder = support.temp_folder()
    local path = folder .. "/tilt.csv"
    support.write_file(path, "# t, rx, ry, rz\n0, 0, 0, 0\n1, 0, 0.3, 0\n2, 0, 0.3, 0\n")
    local tilt = ashlar.ground_motion{ path = path, units = "m/s2" }
    local s = block_on({ 4, 1, 0.2 }, { 0.4, 0.4, 0.2 }, { 0, 0, 0.1 })
    local function run(rotation)
      return ashlar.simulate(s, { duration = 1, friction = 0.2, ground_rotation = rotation }):trajectory(2)
    end
    local from_record = run(tilt)
    assert.same(run(function(t) return tilt(t) end), from_record)
    assert.is_true(from_record.positions[#from_record.positions][1] > 1e-3)  -- tan(0.3) > 0.2: it slid
    support.remove_folder(folder)
  end)

  it("turns the ground of compare_methods' dynamics as it does a simulation's", function()
    -- Tilted by a constant 0.8 rad about y: tan(0.8) = 1.03 > mu 0.7, it slides.
    local s = block_on({ 4, 1, 0.2 }, { 0.4, 0.4, 0.2 }, { 0, 0, 0.1 })
    local function tilted() return 0, 0.8, 0 end
    local c = ashlar.compare_methods(s, { friction = 0.7, margin = false,
      dynamics = { duration = 0.2, ground_rotation = tilted, ground_pivot = { 0, 0, 0 } } })
    local sim = ashlar.simulate(s, { duration = 0.2, friction = 0.7, ground_rotation = tilted })
    assert.is_true(sim.moved)
    assert.equal(sim.max_displacement, c.displacement)
  end)

  it("names the option and the value of a bad rotation or pivot", function()
    local s = block_on({ 3, 1, 0.2 }, { 0.3, 0.4, 0.3 }, { 0, 0, 0.15 })
    support.expect_error({ "ground_rotation: expected a GroundMotion (ashlar.ground_motion) or a function(t) " ..
      "returning rx, ry, rz (rad, a rotation vector), got string" }, function()
      ashlar.simulate(s, { duration = 0.01, ground_rotation = "tilt" })
    end)
    support.expect_error({ "ground_rotation: the function must return three finite numbers rx, ry, rz (rad, a " ..
      "rotation vector); at t = 0.005 its result 2 is ", "nan" }, function()
      ashlar.simulate(s, { duration = 0.01, ground_rotation = function(t) return 0, t > 0.004 and 0 / 0 or 0, 0 end })
    end)
    support.expect_error({ "ground_rotation: the function must return three finite numbers", "its result 3 is nil" },
      function() ashlar.simulate(s, { duration = 0.01, ground_rotation = function() return 0, 0 end }) end)
    support.expect_error({ "ground_pivot" }, function()
      ashlar.simulate(s, { duration = 0.01, ground_pivot = "origin" })
    end)
    support.expect_error({ "ground_pivot[2]: expected a finite number, got inf" }, function()
      ashlar.simulate(s, { duration = 0.01, ground_pivot = { 0, math.huge, 0 } })
    end)
  end)
end)
