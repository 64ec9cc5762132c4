-- ashlar.load_factor and ashlar.friction_demand from Lua: arches against an
-- independent reference (the kinematic theorem over every four-hinge
-- mechanism, tests/lua/four_hinge.lua) and against ashlar.analyze's own
-- verdict just inside and just outside the limit.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local four_hinge = require "four_hinge"
local expect_error, near = support.expect_error, support.near

local NO_SLIDING = { friction = math.huge }

-- Whether the arch stands with `factor` times each voussoir's weight along +x, as
-- point loads at the centroids (ashlar.analyze: the interior-point solver).
local function stands_with(arch_options, factor, options)
  return ashlar.analyze(support.push_laterally(models.arch(arch_options), factor), options).stable
end

describe("ashlar.load_factor", function()
  it("equals the four-hinge kinematic factor of semicircular arches, hinges and all", function()
    for _, ratio in ipairs{ 0.15, 0.2, 0.3 } do
      local s = models.arch{ radius = 1, thickness = ratio, voussoirs = 24 }
      local expected, hinges = four_hinge.collapse_factor(s, 24)
      local f = ashlar.load_factor(s, NO_SLIDING)
      assert.equal("optimal", f.status)
      assert.is_true(f.stable)
      near(f.factor, expected, 1e-9 * expected, "t/R " .. ratio)
      assert.equal(4, #f.limit)
      for k, limit in ipairs(f.limit) do
        assert.equal("hinge", limit.mode)
        -- Joint j lies between voussoirs j and j + 1 (0: the left support, 25, n: the right, 26).
        local joint = limit.b == 25 and 0 or limit.a
        assert.equal(hinges[k][1], joint)
      end
    end
  end)

  it("gives the 64-voussoir factors of the closing note (golden values)", function()
    -- Equal to the four-hinge search to 4e-15 (scripts/stability_margins.lua).
    local golden = { [0.15] = 0.14469729900464, [0.2] = 0.28393741077998, [0.3] = 0.51826354234922 }
    for ratio, expected in pairs(golden) do
      local f = ashlar.load_factor(models.arch{ radius = 1, thickness = ratio, voussoirs = 64 }, NO_SLIDING)
      near(f.factor, expected, 1e-9 * expected, "t/R " .. ratio)
    end
  end)

  it("agrees with ashlar.analyze on either side of the factor, with and without sliding", function()
    local options = { radius = 5, thickness = 0.9, voussoirs = 16 }
    for _, friction in ipairs{ math.huge, 0.35 } do
      local f = ashlar.load_factor(models.arch(options), { friction = friction })
      assert.equal("optimal", f.status)
      assert.is_true(stands_with(options, f.factor * (1 - 1e-4), { friction = friction }))
      assert.is_false(stands_with(options, f.factor * (1 + 1e-4), { friction = friction }))
    end
  end)

  it("multiplies point loads with load = 'point_loads'", function()
    -- A point load on the haunch: the arch stands up to factor times it.
    local options = { radius = 5, thickness = 0.9, voussoirs = 16 }
    local function loaded(scale)
      local s = models.arch(options)
      s:add_load{ block = 5, force = { 0, 0, -scale * 1e4 } }
      return s
    end
    local f = ashlar.load_factor(loaded(1), { load = "point_loads", friction = math.huge })
    assert.equal("optimal", f.status)
    assert.is_true(f.factor > 1)
    assert.is_true(ashlar.analyze(loaded(f.factor * (1 - 1e-4)), NO_SLIDING).stable)
    assert.is_false(ashlar.analyze(loaded(f.factor * (1 + 1e-4)), NO_SLIDING).stable)
  end)

  it("reports an unbounded factor, a mechanism table and option errors", function()
    local s = models.arch{ radius = 1, thickness = 0.2, voussoirs = 12 }
    assert.equal("unbounded", ashlar.load_factor(s, { direction = { 0, 0, -1 } }).status)
    local f = ashlar.load_factor(s)
    assert.equal(#s, #f.mechanism)
    assert.same({ 0, 0, 0 }, f.mechanism[13].velocity)
    expect_error({ "load: 'live' is not one of body_force, point_loads" }, ashlar.load_factor, s, { load = "live" })
    expect_error({ "direction: not with load = 'point_loads'" }, ashlar.load_factor, s,
                 { load = "point_loads", direction = { 1, 0, 0 } })
    expect_error({ "the structure has no point loads" }, ashlar.load_factor, s, { load = "point_loads" })
    expect_error({ "direction", "planar" }, ashlar.load_factor, s, { direction = { 0, 1, 0 } })
    expect_error({ "direction: expected a non-zero" }, ashlar.load_factor, s, { direction = { 0, 0, 0 } })
    expect_error({ "tolerance: only with method = \"kinematic\"" }, ashlar.load_factor, s, { tolerance = 1e-3 })
  end)
end)

describe("ashlar.friction_demand", function()
  it("finds the semicircular arch's at t/R = 0.12 (64 voussoirs) and agrees with ashlar.analyze", function()
    local s = models.arch{ radius = 1, thickness = 0.12, voussoirs = 64 }
    local d = ashlar.friction_demand(s, { tolerance = 1e-9 })
    assert.equal("optimal", d.status)
    near(d.friction, 0.38171575, 1e-6, "golden value")
    assert.is_true(d.lower <= d.friction and d.friction - d.lower <= 1e-9 * d.friction)
    assert.is_true(#d.critical >= 1)
    assert.is_true(ashlar.analyze(s, { friction = d.friction * (1 + 1e-5) }).stable)
    assert.is_false(ashlar.analyze(s, { friction = d.friction * (1 - 1e-5) }).stable)
  end)

  it("is 0 where nothing pushes sideways and infinite where the arch falls anyway", function()
    assert.equal(0, ashlar.friction_demand(models.stack{}).friction)
    -- A running-bond wall under its weight: bed joints carry it, head
    -- joints nothing, no joint needs friction. One program confirms it
    -- (the analyses once halved the coefficient to 4.9e-324 first).
    local wall = ashlar.friction_demand(models.wall{ length = 2.4, height = 0.84 }, { progress = false })
    assert.equal("optimal", wall.status)
    assert.equal(0, wall.friction)
    assert.equal(1, wall.programs)
    local thin = ashlar.friction_demand(models.arch{ radius = 1, thickness = 0.09, voussoirs = 32 })
    assert.equal("unstable", thin.status)
    assert.equal(math.huge, thin.friction)
  end)

  it("checks its options", function()
    local s = models.stack{}
    expect_error({ "unknown option 'friction'" }, ashlar.friction_demand, s, { friction = 0.5 })
    expect_error({ "tolerance: expected a number in (0, 1)" }, ashlar.friction_demand, s, { tolerance = 2 })
  end)
end)
