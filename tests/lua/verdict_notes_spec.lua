-- What a verdict turns on: the joints an unstable structure just misses,
-- warnings on a stable verdict that rests on friction at its limit, and the
-- range of contact tolerances over which the contacts do not change.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local near = support.near

-- Two unit cubes stacked on the ground, the upper pushed 0.7 along x so
-- that its centroid is past the lower's edge, and a support under its
-- overhang whose top is `gap` below it.
local function overhang(gap)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, -0.5 } }, { support = true, name = "ground" })
  s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } }, { name = "lower" })
  s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0.7, 0, 1.5 } }, { name = "upper" })
  s:add(ashlar.box{ size = { 0.5, 1, 2 }, center = { 1.3, 0, -gap } }, { support = true, name = "post" })
  return s
end

-- A block between two walls with nothing under it: the equilibrium method
-- squeezes it (a prestress no load makes), so it stands on friction at its
-- limit; the kinematic method lets it fall.
local function clamped()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 0.2, 1, 1 }, center = { -0.6, 0, 0.5 } }, { support = true })
  s:add(ashlar.box{ size = { 0.2, 1, 1 }, center = { 0.6, 0, 0.5 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.6 } })
  return s
end

describe("an unstable verdict", function()
  it("names its failing blocks and the contact the tolerance just missed", function()
    local s = overhang(0.002)
    local r = ashlar.analyze(s)
    assert.is_false(r.stable)
    assert.are.equal(0, #r.floating)
    assert.is_true(support.contains(r.failing, s:find("upper")))
    local upper = r.blocks[s:find("upper")]
    assert.are.equal(s:find("post"), upper.nearest)
    near(upper.gap, 0.002, 1e-3 * 0.002, "the gap to the post")
    assert.truthy(tostring(r):find("failing block 3 ('upper') is 0.002", 1, true), tostring(r))
    -- That tolerance closes it, and the upper block then rests on the post.
    assert.is_true(ashlar.analyze(s, { contact_tolerance = 1.01 * upper.gap }).stable)
    assert.is_false(support.independent_verdict(s, 0.7))
    assert.is_true(support.independent_verdict(s, 0.7, { tolerance = 1.01 * upper.gap }))
  end)

  it("names none when nothing is within 1 % of the structure's size", function()
    local r = ashlar.analyze(overhang(0.5))
    assert.is_false(r.stable)
    for _, i in ipairs(r.failing) do assert.is_nil(r.blocks[i].nearest) end
    assert.is_nil(tostring(r):find("failing block", 1, true))
  end)
end)

describe("a stable verdict", function()
  it("warns when it rests on friction at its limit", function()
    local s = clamped()
    local r = ashlar.analyze(s, { friction = 0.7 })
    assert.is_true(r.stable)
    assert.are.equal(1, #r.warnings)
    assert.truthy(r.warnings[1]:find("friction is at its limit (mu = 0.7) at 2 of 2 interfaces", 1, true), r.warnings[1])
    assert.truthy(tostring(r):find("1 warning", 1, true))
    -- The warning is right: without prestress the block falls.
    assert.is_false(ashlar.analyze(s, { friction = 0.7, method = "kinematic" }).stable)
  end)

  it("does not warn where friction has room to spare, or sliding is excluded", function()
    for _, case in ipairs{ { "column", models.column{} }, { "dome", models.dome{ meridians = 8, parallels = 5 } },
                           { "wall", models.wall{ length = 1.44, height = 0.35 } } } do
      local r = ashlar.analyze(case[2], { friction = 0.7 })
      assert.is_true(r.stable, case[1])
      assert.are.equal(0, #r.warnings, case[1] .. ": " .. (r.warnings[1] or ""))
    end
    local r = ashlar.analyze(clamped(), { friction = math.huge })
    assert.is_true(r.stable)
    assert.are.equal(0, #r.warnings)
  end)
end)

describe("ashlar.suggest_tolerance", function()
  it("finds the range where an imperfect model's contacts settle", function()
    -- A stack of boxes whose joints open by 1 mm: below that nothing
    -- touches, from it to the next faces (10 cm away) the contacts are
    -- those of the stack.
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 1, 0.1 }, center = { 0, 0, -0.05 } }, { support = true })
    for k = 1, 4 do s:add(ashlar.box{ size = { 0.4, 0.3, 0.1 }, center = { 0, 0, 0.1 * k - 0.05 + 0.001 * k } }) end
    local sweep = ashlar.suggest_tolerance(s, { tolerances = { 1e-4, 3e-4, 9e-4, 1.1e-3, 3e-3, 9e-3, 2.7e-2, 8e-2 } })
    assert.are.equal(8, #sweep.rows)
    assert.are.equal(0, sweep.rows[1].pairs)
    assert.are.equal(4, sweep.rows[1].floating)
    assert.are.equal(4, sweep.rows[4].pairs)
    assert.are.equal(4, sweep.rows[4].new_pairs)
    assert.are.equal(0, sweep.rows[4].floating)
    assert.are.equal(1.1e-3, sweep.lo)
    assert.are.equal(19, #ashlar.suggest_tolerance(s).rows)  -- the default candidates
    assert.are.equal(8e-2, sweep.hi)
    near(sweep.suggested, math.sqrt(1.1e-3 * 8e-2), 1e-15, "suggested")
    assert.is_true(ashlar.analyze(s, { contact_tolerance = sweep.suggested }).stable)
  end)

  it("suggests a range for the Armadillo vault that holds all its joints", function()
    -- Five of the default candidates (scripts/suggest_tolerance.lua prints
    -- all 19): the sweep costs a detection and an overlap check each.
    local s = ashlar.import("../data/compas_cra/armadillo_cra.json", { planarity = 0.05, interfaces = "detect" })
    local sweep = ashlar.suggest_tolerance(s, { tolerances = { 0.003003, 0.006988, 0.01066, 0.03784, 0.1343 } })
    assert.are.equal(5, #sweep.rows)
    assert.are.equal(1042, sweep.rows[2].pairs)
    assert.are.equal(1043, sweep.rows[3].pairs)
    -- From about 1 cm (below, narrow joints are still being found) to over
    -- 10 cm the 1,043 joints are the same (scripts/suggest_tolerance.lua).
    assert.is_true(sweep.lo < 0.011 and sweep.hi > 0.1, ("suggested range %g to %g m"):format(sweep.lo, sweep.hi))
    assert.is_true(ashlar.analyze(s, { friction = 0.84, contact_tolerance = sweep.suggested }).stable)
    assert.are.equal(1043, #s:interfaces{ tolerance = sweep.suggested })
  end)

  it("refuses bad candidates by name", function()
    support.expect_error({ "tolerances", "increasing" }, ashlar.suggest_tolerance, overhang(0.002),
      { tolerances = { 0.01, 0.001 } })
    support.expect_error({ "tolerances[2]", "expected a number" }, ashlar.suggest_tolerance, overhang(0.002),
      { tolerances = { 0.01, "x" } })
    support.expect_error({ "unknown option 'tolerance'" }, ashlar.suggest_tolerance, overhang(0.002), { tolerance = 1 })
  end)
end)
