-- The kinematic method (method = "kinematic") against physics: closed-form
-- cases where rigid-block equilibrium is known to be wrong (friction from
-- normal forces nothing presses in) and cases where both methods must agree.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local function both(s, friction)
  return ashlar.analyze(s, { friction = friction }), ashlar.analyze(s, { friction = friction, method = "kinematic" })
end

-- The structures, shared with scripts/compare_methods.lua (specs run in tests/lua).
local cases = dofile("../../scripts/kinematic_cases.lua")
local clamped, wedge, flat_arch, on_incline, stack = cases.clamped, cases.wedge, cases.flat_arch, cases.incline,
  cases.stack

describe("the kinematic method", function()
  it("lets a block clamped between two walls fall, whatever the friction", function()
    for _, mu in ipairs{ 0.3, 0.9 } do
      local equilibrium, kinematic = both(clamped(), mu)
      assert.is_true(equilibrium.stable)  -- squeezed by normal forces nothing creates
      assert.is_false(kinematic.stable)
      assert.equal("kinematic", kinematic.method)
      assert.equal("converged", kinematic.status)
      -- It falls straight down, sliding along both walls.
      local m = kinematic.mechanism[3]
      assert.near(-1, m.velocity[3], 1e-6)
      assert.near(0, m.velocity[1], 1e-6)
      for k = 1, 3 do assert.near(0, m.rotation[k], 1e-6) end
      assert.equal(2, #kinematic.limit)
      for _, joint in ipairs(kinematic.limit) do assert.equal("sliding", joint.mode) end
      -- Its whole weight is carried by virtual forces.
      assert.near(1, kinematic.infeasibility, 1e-3)
    end
  end)

  it("keeps a wedge seated in a V at any friction", function()
    for _, mu in ipairs{ 0, 0.3, 0.9 } do
      local equilibrium, kinematic = both(wedge(), mu)
      assert.is_true(equilibrium.stable, "mu " .. mu)
      assert.is_true(kinematic.stable, "mu " .. mu)
    end
  end)

  it("lets a flat arch with vertical joints fall, and keeps one whose joints converge below it", function()
    for _, mu in ipairs{ 0.3, 0.6, 0.9 } do
      local equilibrium, kinematic = both(flat_arch(nil), mu)
      assert.is_true(equilibrium.stable)
      assert.is_false(kinematic.stable, "vertical joints, mu " .. mu)
      -- All five voussoirs drop together, sliding along the abutments.
      for i = 3, 7 do assert.near(-1, kinematic.mechanism[i].velocity[3], 1e-6) end
      equilibrium, kinematic = both(flat_arch(1.5), mu)
      assert.is_true(equilibrium.stable)
      assert.is_true(kinematic.stable, "converging joints, mu " .. mu)
    end
  end)

  it("keeps a block on an incline iff tan theta <= mu, as the equilibrium method does", function()
    for _, mu in ipairs{ 0.3, 0.6 } do
      for _, case in ipairs{ { -2, true }, { 2, false } } do
        local theta = math.atan(mu) + math.rad(case[1])
        local equilibrium, kinematic = both(on_incline(theta), mu)
        assert.equal(case[2], equilibrium.stable)
        assert.equal(case[2], kinematic.stable)
        if not case[2] then  -- it slides down the slope
          local v = kinematic.mechanism[2].velocity
          local along = { math.cos(theta), 0, -math.sin(theta) }  -- tilting about +y lowers +x
          local length = math.sqrt(v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2)
          assert.near(1, (v[1] * along[1] + v[3] * along[3]) / length, 1e-3)
        end
      end
    end
  end)

  it("tips a stack at the same overhang as the equilibrium method", function()
    for _, case in ipairs{ { 0.98, true }, { 1.02, false } } do
      local s = stack(case[1])
      local equilibrium, kinematic = both(s, 0.6)
      assert.equal(case[2], equilibrium.stable)
      assert.equal(case[2], kinematic.stable)
    end
  end)

  it("finds a semicircular arch's minimum thickness where the equilibrium method does", function()
    -- 16 polyhedral voussoirs: t/R = 0.10708 (docs/verification.md).
    for _, mu in ipairs{ math.huge, 10, 0.7 } do
      for _, case in ipairs{ { 0.104, false }, { 0.110, true } } do
        local s = models.arch{ radius = 5, thickness = 5 * case[1], voussoirs = 16 }
        local equilibrium, kinematic = both(s, mu)
        assert.equal(case[2], equilibrium.stable)
        assert.equal(case[2], kinematic.stable, ("t/R %g, mu %g"):format(case[1], mu))
      end
    end
  end)

  it("agrees with the equilibrium method on the model library's defaults", function()
    for _, name in ipairs{ "arch", "barrel_vault", "buttressed_vault", "column", "dome", "flying_buttress", "h_frame",
                           "post_and_lintel", "stack", "wall" } do
      local equilibrium, kinematic = both(models[name]{}, 0.7)
      assert.equal(equilibrium.stable, kinematic.stable, name)
      assert.equal("converged", kinematic.status, name)
    end
  end)

  it("says which interfaces the equilibrium method's friction borrowed", function()
    local s = clamped()
    local c = ashlar.compare_methods(s, { friction = 0.6 })
    assert.is_true(c.equilibrium.stable)
    assert.is_false(c.kinematic.stable)
    assert.equal("kinematic", c.kinematic.method)
    -- Each wall holds half the weight by friction, on no compression.
    local weight = 9.81 * s:block(3):mass()
    assert.equal(2, #c.borrowed)
    for _, b in ipairs(c.borrowed) do
      assert.equal(3, b.b)
      assert.near(weight / 2, b.friction, 1e-6 * weight)
      assert.is_true(b.available < 1e-2 * weight)
    end
    assert.equal(0, #ashlar.compare_methods(wedge(), { friction = 0.6 }).borrowed)
  end)

  it("gives a load factor: a block sliding on a floor at mu, a clamped block not standing at all", function()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 3, 3, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
    s:add(ashlar.box{ size = { 1, 1, 0.3 }, center = { 0, 0, 0.15 } })  -- squat: slides before it tips
    local factor = ashlar.load_factor(s, { friction = 0.5, method = "kinematic", tolerance = 1e-3 })
    assert.equal("optimal", factor.status)
    assert.equal("kinematic", factor.method)
    assert.near(0.5, factor.equilibrium_factor, 1e-6)
    assert.is_true(factor.factor <= 0.5 * (1 + 1e-9) and factor.factor >= 0.5 * (1 - 2e-3), tostring(factor.factor))
    local falls = ashlar.load_factor(clamped(), { friction = 0.6, method = "kinematic" })
    assert.equal("unstable", falls.status)
    assert.is_true(falls.factor ~= falls.factor)  -- NaN
    assert.near(-1, falls.mechanism[3].velocity[3], 1e-6)
  end)

  it("gives a friction demand: tan theta on an incline, none finite for a clamped block", function()
    local s = ashlar.tilt((function()
      local flat = ashlar.structure()
      flat:add(ashlar.box{ size = { 4, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
      flat:add(ashlar.box{ size = { 1, 1, 0.3 }, center = { 0, 0, 0.15 } })  -- squat: slides before it tips
      return flat
    end)(), math.rad(20), { origin = { 0, 0, 0 } })
    local demand = ashlar.friction_demand(s, { method = "kinematic", tolerance = 1e-4 })
    assert.equal("optimal", demand.status)
    assert.equal("kinematic", demand.method)
    assert.near(math.tan(math.rad(20)), demand.friction, 2e-4 * math.tan(math.rad(20)))
    assert.is_true(demand.lower <= math.tan(math.rad(20)))
    local clamped_demand = ashlar.friction_demand(clamped(), { method = "kinematic" })
    assert.equal("unbounded", clamped_demand.status)
    assert.equal(math.huge, clamped_demand.friction)
    -- The equilibrium method: any friction at all, squeezed.
    assert.is_true(ashlar.friction_demand(clamped(), {}).friction < 1e-6)
  end)

  it("draws its mechanism: blocks moved rigidly, the fastest centroid by the scale", function()
    local s = stack(1.02)  -- past its overhang: the top blocks tip (rotate)
    local r = ashlar.analyze(s, { friction = 0.6, method = "kinematic" })
    assert.is_false(r.stable)
    local path = os.tmpname() .. ".obj"
    ashlar.export(s, path, { result = r, mechanism = 0.3 })
    local drawn = ashlar.import(path)
    os.remove(path)
    for i = 1, 3 do
      local before, after = s:block(i), drawn:block(drawn:find(s:name(i)))
      local v = r.mechanism[i].velocity
      assert.near(before:volume(), after:volume(), 1e-6)  -- rigid (single precision)
      for k = 1, 3 do assert.near(before:centroid()[k] + 0.3 * v[k], after:centroid()[k], 1e-6) end
    end
    assert.is_true(math.abs(r.mechanism[3].rotation[2]) > 0.1)  -- it turns, not only slides
    support.expect_error({ "mechanism needs an unstable result" }, ashlar.export, clamped(), os.tmpname() .. ".obj",
      { result = ashlar.analyze(clamped(), {}), mechanism = 0.1 })
  end)

  it("names what is wrong with its options", function()
    local s = clamped()
    support.expect_error({ "method: 'dynamic' is not one of equilibrium, kinematic" }, ashlar.analyze, s,
      { method = "dynamic" })
    local r = ashlar.analyze(s, {})
    support.expect_error({ "warm_start: not with method = \"kinematic\"" }, ashlar.analyze, s,
      { method = "kinematic", warm_start = r })
    support.expect_error({ "tolerance: only with method = \"kinematic\"" }, ashlar.load_factor, s, { tolerance = 0.1 })
  end)
end)
