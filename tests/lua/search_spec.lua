-- ashlar.geometric_factor and ashlar.refine: the semicircular arch's
-- minimum thickness (Milankovitch's t/R = 0.1075; docs/api.md "Default
-- discretisations") found by the bracketing search and checked against an
-- independent grid scan, every way a search can end, the coarsest adequate
-- count of a discretisation, and bad input.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local expect_error, near = support.expect_error, support.near

local NO_SLIDING = { friction = math.huge }

-- models.arch with radius 5 and `voussoirs`, as a function of its thickness.
local function arch_of(voussoirs)
  return function(t) return models.arch{ radius = 5, thickness = t, voussoirs = voussoirs } end
end

-- The smallest standing value on a grid from `from` (which must fall) in
-- steps of `step`, refined tenfold in the cell below the first standing
-- point `levels` times: a scan that shares nothing with the search.
local function scanned_minimum(stands, from, step, levels)
  assert(not stands(from), "the scan must start where the model falls")
  local first
  for _ = 1, levels do
    first = from + step
    while not stands(first) do first = first + step end
    from, step = first - step, step / 10
  end
  return first
end

-- A box b wide and h high on a support slab: it stands at any size.
local function box_on_table(h)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 1, 1, h }, center = { 0, 0, h / 2 } }, { name = "box" })
  s:add(ashlar.box{ size = { 2, 2, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "table" })
  return s
end

-- Every analysed value agrees with the final bracket (stability is
-- monotone in the thickness), and the bracket's ends were analysed.
local function expect_consistent_history(g)
  assert.equal(g.analyses, #g.history)
  local seen = {}
  for _, h in ipairs(g.history) do
    if h.value >= g.upper then assert.is_true(h.stable, "stands at " .. h.value) end
    if h.value <= g.lower then assert.is_false(h.stable, "falls at " .. h.value) end
    assert.equal(h.stable, h.infeasibility == 0)
    assert.is_true(h.iterations > 0 and h.seconds >= 0)
    seen[h.value] = h.stable
  end
  assert.is_true(seen[g.upper]); assert.is_false(seen[g.lower])
end

describe("geometric_factor", function()
  it("finds the minimum thickness of a 512-voussoir semicircular arch: t/R 0.10748, Milankovitch's 0.1075", function()
    local g = ashlar.geometric_factor(arch_of(512), 0.75, NO_SLIDING)
    assert.equal("converged", g.status)
    local ratio = g.minimum / 5
    assert.is_true(math.abs(ratio / 0.10748 - 1) <= 1e-4, "t/R " .. ratio)
    assert.is_true(math.abs(ratio / 0.1075 - 1) <= 1e-3, "t/R " .. ratio)
    -- t = 0.75 is t/R = 0.15: Heyman's geometric factor of safety.
    near(g.factor, 0.75 / g.minimum, 1e-15)
    near(g.factor, 0.15 / 0.10748, 1e-3)
    assert.equal(g.upper, g.minimum)
    assert.is_true(g.lower < g.upper and g.upper - g.lower <= 1e-6 * g.upper)
    expect_consistent_history(g)
    assert.is_true(g.seconds > 0)
  end)

  it("agrees with the default discretisation's error in docs/api.md and with a grid scan", function()
    local g = ashlar.geometric_factor(arch_of(24), 0.75, NO_SLIDING)
    assert.equal("converged", g.status)
    -- 24 voussoirs: -0.35 % from 0.53739 m (rounded to 0.01 %).
    assert.is_true(math.abs(g.minimum / 0.53739 - 1 + 0.0035) <= 0.0001, "minimum " .. g.minimum)
    local scanned = scanned_minimum(function(t) return ashlar.analyze(arch_of(24)(t), NO_SLIDING).stable end,
                                    0.5, 0.01, 4)
    assert.is_true(scanned - 1e-5 <= g.lower and g.upper <= scanned, ("scan %.7f, bracket %.7f..%.7f"):format(scanned, g.lower, g.upper))
    expect_consistent_history(g)
    -- Halving from the current value brackets the change, then bisection.
    assert.are.same({ 0.75, 0.375, 0.5625 }, { g.history[1].value, g.history[2].value, g.history[3].value })
  end)

  it("searches upwards from a current value that falls, to the same minimum", function()
    local down = ashlar.geometric_factor(arch_of(16), 0.75, NO_SLIDING)
    local up = ashlar.geometric_factor(arch_of(16), 0.3, NO_SLIDING)
    assert.equal("converged", up.status)
    assert.is_false(up.history[1].stable)
    assert.are.same({ 0.3, 0.6 }, { up.history[1].value, up.history[2].value })
    assert.is_true(math.abs(up.minimum - down.minimum) <= 2e-6 * down.minimum)
    -- The polyhedral arch's thrust-line minimum (tests/lua/models_spec.lua).
    near(up.minimum / 5, 0.1070762, 1e-6)
    near(up.factor, 0.3 / up.minimum, 1e-15)
    assert.is_true(up.factor < 1)
    expect_consistent_history(up)
  end)

  it("takes another criterion: stands(s, value) replaces the analysis", function()
    -- Standing is not enough: the arch must also weigh what it does at t = 0.6
    -- (its volume N R t sin(pi/N) is linear in t), so the minimum is 0.6.
    local needed = support.free_volume(arch_of(16)(0.6))
    local values = {}
    local g = ashlar.geometric_factor(arch_of(16), 0.75, {
      tolerance = 1e-8,
      stands = function(s, value)
        values[#values + 1] = value
        return ashlar.analyze(s, NO_SLIDING).stable and support.free_volume(s) >= needed * (1 - 1e-12)
      end,
    })
    assert.equal("converged", g.status)
    near(g.minimum, 0.6, 1e-8 * 0.6)
    near(g.factor, 0.75 / 0.6, 1e-7)
    for k, h in ipairs(g.history) do
      assert.equal(values[k], h.value)
      assert.is_nil(h.infeasibility)
    end
    -- The default criterion finds the arch's own, smaller minimum.
    assert.is_true(ashlar.geometric_factor(arch_of(16), 0.75, NO_SLIDING).minimum < 0.54)
  end)

  it("stops at the smallest value allowed when the model still stands there", function()
    local g = ashlar.geometric_factor(box_on_table, 0.8, { lower = 0.1 })
    assert.equal("stable_at_lower", g.status)
    assert.equal(0.1, g.minimum); near(g.factor, 8, 1e-15)
    assert.equal(0.1, g.upper); assert.is_nil(g.lower)
    assert.are.same({ 0.8, 0.4, 0.2, 0.1 }, { g.history[1].value, g.history[2].value, g.history[3].value, g.history[4].value })
    -- Without `lower`, down to a millionth of the value, never 0.
    local floor = ashlar.geometric_factor(box_on_table, 0.8)
    assert.equal("stable_at_lower", floor.status)
    near(floor.minimum, 0.8e-6, 1e-21)
    near(floor.factor, 1e6, 1e-6)
    assert.equal(21, floor.analyses)
  end)

  it("gives up at `upper` when nothing stands", function()
    -- A stack whose top block overhangs by 0.9 of its length never stands.
    local g = ashlar.geometric_factor(function() return models.stack{ blocks = 2, offset = 0.9 } end, 1, { upper = 8 })
    assert.equal("unstable_at_upper", g.status)
    assert.is_nil(g.minimum); assert.equal(0, g.factor)
    assert.equal(8, g.lower); assert.is_nil(g.upper)
    assert.equal(4, g.analyses)  -- 1, 2, 4, 8
  end)

  it("stops after max_analyses with the bracket so far", function()
    local g = ashlar.geometric_factor(arch_of(16), 0.75, { friction = math.huge, max_analyses = 5 })
    assert.equal("max_analyses", g.status)
    assert.equal(5, g.analyses)
    -- 0.75 stands, 0.375 falls, 0.5625 stands, 0.46875 and 0.515625 fall.
    assert.equal(0.5625, g.minimum); assert.equal(0.5625, g.upper); assert.equal(0.515625, g.lower)
    near(g.factor, 0.75 / 0.5625, 1e-15)
  end)

  it("rejects bad arguments and reports the model's failures with the value", function()
    local arch = arch_of(8)
    expect_error({ "model_fn: expected a function(value) returning a Structure, got nil" }, ashlar.geometric_factor, nil, 1)
    expect_error({ "geometric_factor: model_fn(0.3) returned a number, expected a Structure" },
                 ashlar.geometric_factor, function() return 42 end, 0.3)
    expect_error({ "geometric_factor: model_fn(0.3) returned nil, expected a Structure" },
                 ashlar.geometric_factor, function() end, 0.3)
    expect_error({ "geometric_factor: model_fn(0.3) failed: ", "search_spec.lua:", "no such model" },
                 ashlar.geometric_factor, function() error("no such model") end, 0.3)
    expect_error({ "model_fn(0.3) failed", "models.arch" },
                 ashlar.geometric_factor, function(t) return models.arch{ radius = 0.1, thickness = t } end, 0.3)
    for _, value in ipairs{ 0, -1 } do
      expect_error({ "value: expected a number > 0" }, ashlar.geometric_factor, arch, value)
    end
    expect_error({ "value: expected a finite number, got nan" }, ashlar.geometric_factor, arch, 0 / 0)
    expect_error({ "value: expected a number, got string" }, ashlar.geometric_factor, arch, "0.75")
    expect_error({ "unknown option 'tol'", "max_analyses", "stands", "friction" }, ashlar.geometric_factor, arch, 0.75, { tol = 1 })
    expect_error({ "tolerance: expected a number > 0" }, ashlar.geometric_factor, arch, 0.75, { tolerance = 0 })
    expect_error({ "tolerance: expected a number in (0, 1)" }, ashlar.geometric_factor, arch, 0.75, { tolerance = 1.5 })
    expect_error({ "lower: expected a number >= 0 and < value (0.75), got 1" }, ashlar.geometric_factor, arch, 0.75, { lower = 1 })
    expect_error({ "upper: expected a number > value (0.75), got 0.5" }, ashlar.geometric_factor, arch, 0.75, { upper = 0.5 })
    expect_error({ "max_analyses: expected a whole number >= 1, got 0" }, ashlar.geometric_factor, arch, 0.75, { max_analyses = 0 })
    expect_error({ "friction: expected a number >= 0" }, ashlar.geometric_factor, arch, 0.75, { friction = -1 })
    expect_error({ "stands: expected a function(s, value)" }, ashlar.geometric_factor, arch, 0.75, { stands = true })
    expect_error({ "friction: analysis options apply to the default criterion" },
                 ashlar.geometric_factor, arch, 0.75, { friction = 0.5, stands = function() return true end })
    expect_error({ "geometric_factor: stands(s, 0.75) returned nil, expected a boolean" },
                 ashlar.geometric_factor, arch, 0.75, { stands = function() end })
  end)
end)

describe("refine", function()
  -- A small structure per count, remembered to check which one comes back.
  local made
  local function model(n)
    made[n] = models.stack{ blocks = 1 }
    return made[n]
  end
  before_each(function() made = {} end)

  it("stops when a change is within tolerance and returns the coarsest count within it of the finest", function()
    local function f(n) return 1 + 1 / n ^ 2 end
    local r = ashlar.refine(model, function(s, n)
      assert.equal(made[n], s)
      assert.equal("integer", math.type(n))
      return f(n)
    end, { start = 4, tolerance = 1e-3, confirm = 1 })
    -- Changes: 4.6 %, 1.2 %, 0.29 %, 0.073 %: stop at 64. From 64's value,
    -- 32 is 0.073 % off, 16 0.37 %: 32 is the coarsest adequate count.
    assert.is_true(r.converged)
    assert.equal(32, r.count); assert.equal(f(32), r.value); assert.equal(f(64), r.reference)
    assert.equal(made[32], r.structure)
    assert.equal(5, #r.history)
    for k, h in ipairs(r.history) do
      local n = 2 ^ (k + 1)
      assert.equal(n, h.count); assert.equal("integer", math.type(h.count)); assert.equal(f(n), h.value)
      if k == 1 then assert.is_nil(h.change) else near(h.change, math.abs(f(n) - f(n / 2)) / f(n), 1e-15) end
      assert.is_true(h.seconds >= 0)
    end
    assert.is_true(r.seconds > 0)
    -- Two settled changes in a row (the default): on to 128, and 32 is
    -- still the coarsest.
    local confirmed = ashlar.refine(model, function(_, n) return f(n) end, { start = 4, tolerance = 1e-3 })
    assert.equal(6, #confirmed.history); assert.equal(32, confirmed.count); assert.equal(f(128), confirmed.reference)
  end)

  it("does not take a lucky coarse count followed by a poor one", function()
    local values = { [4] = 1.0, [8] = 1.5, [16] = 1.004, [32] = 1.001 }
    local r = ashlar.refine(model, function(_, n) return values[n] end, { start = 4, confirm = 1 })
    -- 4 is within 1 % of 32's value, but 8 is not: 16 is the coarsest adequate.
    assert.is_true(r.converged)
    assert.equal(16, r.count); assert.equal(1.004, r.value); assert.equal(1.001, r.reference)
  end)

  it("grows by max(n + 1, ceil(n * growth)) up to max, and returns the finest count unconverged", function()
    local r = ashlar.refine(model, function(_, n) return n end, { start = 4, growth = 1.5, max = 20 })
    assert.is_false(r.converged)
    local counts = {}
    for k, h in ipairs(r.history) do counts[k] = h.count end
    assert.are.same({ 4, 6, 9, 14, 20 }, counts)
    assert.equal(20, r.count); assert.equal(20, r.value); assert.equal(20, r.reference)
    assert.equal(made[20], r.structure)
    local slow = ashlar.refine(model, function(_, n) return n end, { start = 4, growth = 1, max = 7 })
    assert.equal(4, #slow.history); assert.equal(7, slow.count)
  end)

  it("finds the coarsest adequate semicircular arch for its minimum thickness, within 1 % of 0.53739 m", function()
    local function minimum_thickness(_, n)
      return ashlar.geometric_factor(arch_of(n), 0.75, { friction = math.huge, tolerance = 1e-5 }).minimum
    end
    local r = ashlar.refine(function(n) return models.arch{ radius = 5, voussoirs = n } end, minimum_thickness,
                            { start = 8, tolerance = 0.01 })
    -- 8 voussoirs are 7 % thin; 16 and 32 agree within 1 %. References:
    -- the polyhedral arch's thrust-line minima (tests/lua/models_spec.lua).
    assert.is_true(r.converged)
    assert.equal(16, r.count)
    assert.equal(18, #r.structure)
    assert.are.same({ 8, 16, 32 }, { r.history[1].count, r.history[2].count, r.history[3].count })
    near(r.history[1].value / 5, 0.0999717, 2e-6)
    near(r.history[2].value / 5, 0.1070762, 2e-6)
    for _, value in ipairs{ r.value, r.reference } do
      assert.is_true(math.abs(value / 0.53739 - 1) <= 0.01, "minimum " .. value)
    end
  end)

  it("rejects bad arguments and reports bad metrics with the count", function()
    local function metric() return 1 end
    expect_error({ "model_fn: expected a function(n)" }, ashlar.refine, nil, metric)
    expect_error({ "metric_fn: expected a function(s, n) returning a number, got number" }, ashlar.refine, model, 1)
    expect_error({ "refine: metric_fn(s, 4) returned a string, expected a number" },
                 ashlar.refine, model, function() return "1" end)
    expect_error({ "refine: metric_fn(s, 8) returned nil, expected a number" },
                 ashlar.refine, model, function(_, n) if n == 4 then return 1 end end)
    expect_error({ "refine: metric_fn(s, 4) returned ", "nan, expected a finite number" },
                 ashlar.refine, model, function() return 0 / 0 end)
    expect_error({ "refine: metric_fn(s, 4) failed: ", "search_spec.lua:", "bad metric" },
                 ashlar.refine, model, function() error("bad metric") end)
    expect_error({ "refine: model_fn(4) returned a table, expected a Structure" }, ashlar.refine, function() return {} end, metric)
    expect_error({ "unknown option 'min'", "confirm, growth, max, start, tolerance" }, ashlar.refine, model, metric, { min = 2 })
    expect_error({ "start: expected a whole number >= 1, got 0" }, ashlar.refine, model, metric, { start = 0 })
    expect_error({ "start: expected a whole number <= max (16), got 32" }, ashlar.refine, model, metric, { start = 32, max = 16 })
    expect_error({ "growth: expected a number >= 1" }, ashlar.refine, model, metric, { growth = 0.5 })
    expect_error({ "confirm: expected a whole number >= 1, got 1.5" }, ashlar.refine, model, metric, { confirm = 1.5 })
    expect_error({ "tolerance: expected a number > 0" }, ashlar.refine, model, metric, { tolerance = -0.01 })
  end)
end)
