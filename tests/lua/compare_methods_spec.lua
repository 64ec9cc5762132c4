-- The arbiter between the methods (ashlar.compare_methods, and
-- ashlar.analyze with method = "auto") against physics and closed forms:
-- free fall, a drop onto a floor, the friction demand of a block on an
-- incline, and a block clamped between walls, where the static methods
-- disagree and the dynamics from rest decides.
local ashlar = require "ashlar"
local support = require "spec_support"

local cases = dofile("../../scripts/kinematic_cases.lua")
local g = 9.81

describe("ashlar.compare_methods' verdict", function()
  it("lets the dynamics decide for a block clamped between walls: it falls freely", function()
    local c = ashlar.compare_methods(cases.clamped(), { friction = 0.6, cra = true })
    assert.equal("stands", c.methods.equilibrium)  -- squeezed by normal forces nothing creates
    assert.equal("falls", c.methods.kinematic)
    assert.equal("falls", c.methods.dynamics)
    assert.equal("falls", c.methods.cra)  -- no compatible compression-only equilibrium
    assert.equal("falls", c.verdict)
    assert.is_false(c.stable)
    assert.equal("dynamics", c.decided_by)
    -- Nothing touches it but the walls, which hold nothing: free fall,
    -- 1/2 g t^2 in the default quarter of a second.
    support.near(c.displacement, 0.5 * g * 0.25 ^ 2, 1e-6, "displacement")
    assert.equal(3, c.displaced_block)
    assert.is_nil(c.friction_demand)  -- no margin for what falls
    assert.truthy(c.reason:find("dynamics: falls (from rest, block 3 moved 0.307 m in 0.25 s, still moving)", 1, true),
      c.reason)
    assert.is_true(c.dynamic.moved)
    assert.equal("cra", c.cra.method)
  end)

  it("gives CRA's verdict when the dynamics is not asked for, and none without either", function()
    assert.is_nil(ashlar.compare_methods(cases.clamped(), { friction = 0.6 }).cra)  -- only when asked for
    local c = ashlar.compare_methods(cases.clamped(), { friction = 0.6, dynamics = false, cra = true })
    assert.is_nil(c.dynamic)
    assert.equal("falls", c.verdict)
    assert.equal("cra", c.decided_by)
    local none = ashlar.compare_methods(cases.clamped(), { friction = 0.6, dynamics = false })
    assert.equal("no verdict", none.verdict)
    assert.is_false(none.stable)
    assert.is_nil(none.decided_by)
    assert.is_nil(none.cra)
  end)

  it("takes the static methods' word where they settle it, with the friction margin", function()
    -- A squat block on an incline at theta: it slides at tan theta, the
    -- least friction it stands on (it tips only at tan theta = 2).
    local theta = math.atan(0.6) - math.rad(2)
    local stands = ashlar.compare_methods(cases.incline(theta), { friction = 0.6 })
    assert.equal("stands", stands.verdict)
    assert.equal("both", stands.decided_by)
    assert.is_nil(stands.dynamic)  -- not needed
    assert.is_nil(stands.cra)
    support.near(stands.friction_demand, math.tan(theta), 1e-2 * math.tan(theta), "friction demand")
    support.near(stands.margin, 0.6 / stands.friction_demand, 1e-12, "margin")
    local falls = ashlar.compare_methods(cases.incline(math.atan(0.6) + math.rad(2)), { friction = 0.6 })
    assert.equal("falls", falls.verdict)
    assert.equal("equilibrium", falls.decided_by)
    assert.is_nil(falls.dynamic)
    -- The wedge in a V stands without friction: demand 0, margin infinite.
    local wedge = ashlar.compare_methods(cases.wedge(), { friction = 0.6 })
    assert.equal("stands", wedge.verdict)
    assert.equal(0, wedge.friction_demand)
    assert.equal(math.huge, wedge.margin)
    assert.is_nil(ashlar.compare_methods(cases.wedge(), { friction = 0.6, margin = false }).friction_demand)
  end)

  it("runs the dynamics when asked even where the static methods agree: a block dropped 1 cm settles", function()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 2, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
    s:add(ashlar.box{ size = { 0.5, 0.5, 0.3 }, center = { 0, 0, 0.15 + 0.01 } })
    local c = ashlar.compare_methods(s, { friction = 0.6, dynamics = { duration = 0.3 }, contact_tolerance = 1e-3 })
    assert.equal("falls", c.verdict)  -- it floats: no contact within 1 mm
    assert.equal("equilibrium", c.decided_by)
    assert.equal("settles", c.methods.dynamics)  -- it lands flat and stays (plastic impact)
    support.near(c.displacement, 0.01, 1e-3, "displacement")
  end)
end)

describe("ashlar.analyze with method = 'auto'", function()
  it("returns the Result of the method that agrees with the verdict, the verdict in r.check", function()
    local r = ashlar.analyze(cases.clamped(), { friction = 0.6, method = "auto" })
    assert.equal("kinematic", r.method)  -- its mechanism: straight down
    assert.is_false(r.stable)
    support.near(r.mechanism[3].velocity[3], -1, 1e-6, "mechanism")
    assert.equal("falls", r.check.verdict)
    assert.equal("dynamics", r.check.decided_by)
    assert.truthy(tostring(r):find("checked: falls", 1, true), tostring(r))
    local wedge = ashlar.analyze(cases.wedge(), { friction = 0.6, method = "auto" })
    assert.is_true(wedge.stable)
    assert.equal("kinematic", wedge.method)
    assert.equal("both", wedge.check.decided_by)
    assert.is_nil(ashlar.analyze(cases.wedge(), { friction = 0.6 }).check)
  end)

  it("names what is wrong", function()
    support.expect_error({ "method: 'automatic' is not one of equilibrium, kinematic, cra, cra_penalty, auto" },
      ashlar.analyze, cases.wedge(), { method = "automatic" })
    support.expect_error({ "verdict_only: not with method = 'auto'" }, ashlar.analyze, cases.wedge(),
      { method = "auto", verdict_only = true })
    support.expect_error({ "dynamics: expected true or false, got string" }, ashlar.compare_methods, cases.wedge(),
      { dynamics = "yes" })
    support.expect_error({ "cra: expected true or false, got number" }, ashlar.compare_methods, cases.wedge(),
      { cra = 1 })
  end)
end)
