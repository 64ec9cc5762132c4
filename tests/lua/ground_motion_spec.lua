-- ashlar.ground_motion (recorded accelerograms) and the Simulation's
-- engineer's summary as a user calls them: the synthetic records of
-- tests/data/ground_motion (a triangular pulse, 0.25 g at 0.25 s, -0.25 g at
-- 0.75 s, 0 at 1 s, sampled at its corners: linear interpolation gives the
-- function exactly), used as ground_acceleration; sim:summary, sim:drift and
-- sim:chart; the errors.
local ashlar = require "ashlar"
local support = require "spec_support"

local data = "../data/ground_motion/"
local g = 9.81

-- The pulse (g) at time t (s).
local function triangle(t)
  if t < 0 or t > 1 then return 0 end
  if t <= 0.25 then return t end
  if t <= 0.75 then return 0.5 - t end
  return t - 1
end

describe("ashlar.ground_motion", function()
  it("reads a PEER AT2 record, scales it and gives the function exactly between samples", function()
    local gm = ashlar.ground_motion{ path = data .. "triangle.at2", scale = 0.5, component = "y" }
    for _, t in ipairs{ -1, 0, 0.013, 0.25, 0.61, 0.999, 1, 3 } do
      local ax, ay, az = gm(t)
      assert.equal(0, ax)
      support.near(ay, 0.5 * g * triangle(t), 1e-12, "t = " .. t)
      assert.equal(0, az)
    end
    assert.equal(1, gm.duration)
    support.near(gm.peak, 0.5 * 0.25 * g, 1e-12)
    support.near(gm.peak_time, 0.25, 1e-12)
    assert.equal(1, gm.components)
    assert.equal(21, gm.samples)
    assert.matches("^GroundMotion %(1 component%(s%), 1 s, peak 1.23 m/s%^2 at 0.25 s%)$", tostring(gm))
  end)

  it("maps a table's columns onto axes in the stated units, and files onto axes", function()
    local gm = ashlar.ground_motion{ path = data .. "triangle.csv", units = "g", component = { "x", "z" } }
    local ax, ay, az = gm(0.4)
    support.near(ax, g * triangle(0.4), 1e-12)
    assert.equal(0, ay)
    support.near(az, 0.5 * g * triangle(0.4), 1e-12)
    local in_si = ashlar.ground_motion{ path = data .. "triangle.csv", units = "m/s2" }  -- columns along x, y
    ax, ay = in_si(0.4)
    support.near(ax, triangle(0.4), 1e-12)
    support.near(ay, 0.5 * triangle(0.4), 1e-12)
    local two = ashlar.ground_motion{ path = { y = data .. "triangle.at2", x = data .. "triangle.at2" } }
    ax, ay = two(0.1)
    support.near(ax, g * 0.1, 1e-12)
    support.near(ay, g * 0.1, 1e-12)
    -- Baseline: the pulse's samples average 0, so removing the mean changes nothing.
    local mean = ashlar.ground_motion{ path = data .. "triangle.at2", baseline = "mean" }
    support.near(mean(0.3), g * triangle(0.3), 1e-12)
  end)

  it("shakes a structure as the function it samples does", function()
    local function structure()
      local s = ashlar.structure()
      s:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true })
      s:add(ashlar.box{ size = { 0.3, 0.3, 0.3 }, center = { 0, 0, 0.15 } })
      return s
    end
    -- 0.25 g beats friction 0.2: the block slides.
    local opts = { duration = 1.2, friction = 0.2 }
    opts.ground_acceleration = ashlar.ground_motion{ path = data .. "triangle.at2" }
    local recorded = ashlar.simulate(structure(), opts)
    opts.ground_acceleration = function(t) return g * triangle(t), 0, 0 end
    local analytic = ashlar.simulate(structure(), opts)
    assert.is_true(recorded.moved)
    support.near(recorded.max_displacement, analytic.max_displacement, 1e-9 * analytic.max_displacement)
  end)

  it("names the file, the line and the value of a malformed record, and the bad option", function()
    local bad = os.tmpname()
    local f = assert(io.open(bad, "w"))
    f:write("time,a\n0,0\n0.1,0.2\n0.2,oops\n")
    f:close()
    support.expect_error({ bad .. ":4: expected an acceleration, got \"oops\"" },
      function() ashlar.ground_motion{ path = bad, units = "g" } end)
    os.remove(bad)
    support.expect_error({ "units: required for a table", "\"g\", \"m/s2\" or \"cm/s2\"" },
      function() ashlar.ground_motion{ path = data .. "triangle.csv" } end)
    support.expect_error({ "units: an AT2 file states its units in its header" },
      function() ashlar.ground_motion{ path = data .. "triangle.at2", units = "g" } end)
    support.expect_error({ "component: expected an axis \"x\", \"y\" or \"z\", got \"w\"" },
      function() ashlar.ground_motion{ path = data .. "triangle.at2", component = "w" } end)
    support.expect_error({ "has 2 acceleration column(s) but component names 1 axis(es)" },
      function() ashlar.ground_motion{ path = data .. "triangle.csv", units = "g", component = "x" } end)
    support.expect_error({ "baseline: 'quadratic' is not one of none, mean, linear" },
      function() ashlar.ground_motion{ path = data .. "triangle.at2", baseline = "quadratic" } end)
    support.expect_error({ "cannot open" }, function() ashlar.ground_motion{ path = data .. "none.at2" } end)
    support.expect_error({ "ground_acceleration: expected a GroundMotion (ashlar.ground_motion) or a function(t)" },
      function() ashlar.simulate(ashlar.structure(), { ground_acceleration = 1 }) end)
  end)
end)

describe("the Simulation's summary", function()
  it("reports peak and residual displacement, drift, first movement, collapse and a chart", function()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 3, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "floor" })
    s:add(ashlar.box{ size = { 0.4, 0.4, 0.2 }, center = { 0, 0, 0.1 } }, { name = "sliding" })
    s:add(ashlar.box{ size = { 0.4, 0.4, 0.2 }, center = { 5, 0, 1 } }, { name = "falling" })
    -- A constant 0.5 g push against friction 0.3: the block slides at 0.2 g
    -- from the start, 1/2 (0.2 g) t^2; the other block falls freely.
    local sim = ashlar.simulate(s, { duration = 0.4, friction = 0.3, record_every = 1, tolerance = 1e-8,
                                     ground_acceleration = function() return -0.5 * g, 0, 0 end })
    local summary = sim:summary()
    local slid = 0.5 * 0.2 * g * 0.4 ^ 2
    support.near(summary.residual_displacements[2], slid, 0.01 * slid)
    assert.equal(0, summary.residual_displacements[1])
    assert.equal(3, summary.peak_block)
    assert.is_true(summary.collapsed)
    assert.same({ 3 }, summary.fallen)
    support.near(summary.collapse_time, math.sqrt(2 * 0.1 / g), 1e-3)   -- dropped half its 0.2 m height
    assert.is_true(summary.first_movement <= 0.02)
    local d = sim:drift("sliding")
    support.near(d.height, 0.1, 1e-12)                       -- centroid over the lowest free vertex
    support.near(d.residual, slid / 0.1, 0.01 * slid / 0.1)
    assert.equal(sim.frames, #d.values)
    local folder = os.tmpname()
    os.remove(folder)
    local chart = sim:chart{ path = folder .. ".png", blocks = { "sliding", 3 } }
    assert.same({ "sliding", "falling" }, { chart.series[1].name, chart.series[2].name })
    assert.equal(sim.frames, chart.series[1].points)
    local drift_chart = sim:chart{ path = folder .. ".svg", quantity = "drift", blocks = 2 }
    assert.equal("drift of sliding", drift_chart.series[1].name)
    os.remove(folder .. ".png")
    os.remove(folder .. ".svg")
    support.expect_error({ "quantity: expected \"displacement\" or \"drift\", got \"speed\"" },
      function() sim:chart{ path = "x.png", quantity = "speed" } end)
    support.expect_error({ "drift: block 1 is a support, which does not move" }, function() sim:drift(1) end)
    support.expect_error({ "fall_fraction: expected" }, function() sim:summary{ fall_fraction = -1 } end)
  end)
end)
