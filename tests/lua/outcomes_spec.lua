-- How the margin searches answer and what they are asked: the status
-- strings scripts compare (one table per engine status enum), the bracket
-- width's own name `bracket_tolerance` and its older name `tolerance`, and
-- the defaults docs/api.md documents, against what the functions do when
-- the option is left out.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local expect_error = support.expect_error

-- A squat block on a floor: it slides at mu before it tips.
local function squat_block()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 3, 3, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.3 }, center = { 0, 0, 0.15 } })
  return s
end

-- The same block on a floor tilted by 20 degrees: a friction demand of tan 20.
local function block_on_incline()
  local flat = ashlar.structure()
  flat:add(ashlar.box{ size = { 4, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
  flat:add(ashlar.box{ size = { 1, 1, 0.3 }, center = { 0, 0, 0.15 } })
  return ashlar.tilt(flat, math.rad(20), { origin = { 0, 0, 0 } })
end

local function arch_of(t) return models.arch{ radius = 5, thickness = t, voussoirs = 16 } end

-- The rows of the table in docs/api.md's section `heading` (e.g. "### Friction
-- demand") up to the next heading: { [key] = default cell }.
local function documented_defaults(heading)
  local docs = assert(io.open("../../docs/api.md")):read("a")
  local from = assert(docs:find("\n" .. heading .. "\n", 1, true), heading)
  local to = docs:find("\n#", from + 1, true) or #docs
  local rows = {}
  for key, default in docs:sub(from, to):gmatch("\n| `([%w_]+)` | ([^|]*) |") do rows[key] = default end
  return rows
end

-- The first number in a documented default ("1e-6; 1e-3 with ..." -> 1e-6),
-- and the one after "kinematic" when there is one.
local function numbers_of(cell)
  local first = tonumber(cell:match("^%s*([%d%.e%-]+)"))
  local kinematic = tonumber(cell:match("([%d%.e%-]+) with `method = \"kinematic\"`") or "")
  return first, kinematic
end

describe("status strings", function()
  it("are the engine's names, unchanged", function()
    local arch = models.arch{ radius = 5, thickness = 0.75, voussoirs = 16 }
    local f = ashlar.load_factor(arch, { friction = math.huge })
    assert.equal("optimal", f.status)
    assert.is_true(f.stable)
    local down = ashlar.load_factor(arch, { friction = math.huge, direction = { 0, 0, -1 } })
    assert.equal("unbounded", down.status)
    assert.equal(math.huge, down.factor)
    local floating = squat_block()
    floating:add(ashlar.box{ size = { 1, 1, 1 }, center = { 10, 0, 5 } })
    local lost = ashlar.load_factor(floating, {})
    assert.equal("floating", lost.status)
    assert.is_false(lost.stable)
    assert.equal("floating", ashlar.friction_demand(floating, {}).status)
    local thin = ashlar.friction_demand(models.arch{ radius = 1, thickness = 0.09, voussoirs = 32 })
    assert.equal("unstable", thin.status)
    assert.equal("optimal", ashlar.load_capacity(squat_block(), { progress = false }).status)
    assert.equal("done", ashlar.important_weights(arch, { progress = false }).status)
  end)

  it("come with the kinematic load factor's verdict from the engine", function()
    local slides = ashlar.load_factor(squat_block(), { friction = 0.5, method = "kinematic" })
    assert.equal("optimal", slides.status)
    assert.is_true(slides.stable)
    local unstable = squat_block()
    unstable:add(ashlar.box{ size = { 1, 1, 0.3 }, center = { 0.9, 0, 0.45 } })  -- past the edge below
    local falls = ashlar.load_factor(unstable, { friction = 0.5, method = "kinematic" })
    assert.is_false(falls.stable)
    assert.is_true(falls.factor ~= falls.factor)  -- NaN: no factor
  end)
end)

describe("bracket_tolerance", function()
  it("is the bracket's width, and tolerance its older name, in friction_demand", function()
    local s = arch_of(0.75)
    local new = ashlar.friction_demand(s, { bracket_tolerance = 1e-9 })
    local old = ashlar.friction_demand(s, { tolerance = 1e-9 })
    assert.equal("optimal", new.status)
    assert.equal(old.friction, new.friction)
    assert.equal(old.programs, new.programs)
    assert.is_true(new.friction - new.lower <= 1e-9 * new.friction)
    local coarse = ashlar.friction_demand(s, { bracket_tolerance = 1e-2 })
    assert.is_true(coarse.programs < new.programs)
  end)

  it("is the bisection's width, and tolerance its older name, with method = \"kinematic\"", function()
    local new = ashlar.load_factor(squat_block(), { friction = 0.5, method = "kinematic", bracket_tolerance = 1e-2 })
    local old = ashlar.load_factor(squat_block(), { friction = 0.5, method = "kinematic", tolerance = 1e-2 })
    assert.equal(old.factor, new.factor)
    assert.equal(old.analyses, new.analyses)
    local demand = ashlar.friction_demand(block_on_incline(), { method = "kinematic", bracket_tolerance = 1e-2 })
    assert.equal(ashlar.friction_demand(block_on_incline(), { method = "kinematic", tolerance = 1e-2 }).friction,
                 demand.friction)
  end)

  it("is the geometric factor's bracket, and tolerance its older name", function()
    local new = ashlar.geometric_factor(arch_of, 0.75, { friction = math.huge, bracket_tolerance = 1e-3 })
    local old = ashlar.geometric_factor(arch_of, 0.75, { friction = math.huge, tolerance = 1e-3 })
    assert.equal("converged", new.status)
    assert.equal(old.minimum, new.minimum)
    assert.equal(old.analyses, new.analyses)
    assert.is_true(new.upper - new.lower <= 1e-3 * new.upper)
  end)

  it("refuses both names at once, and names the one given", function()
    local s = squat_block()
    local both = { "bracket_tolerance, tolerance: give one of them" }
    expect_error(both, ashlar.friction_demand, s, { bracket_tolerance = 1e-3, tolerance = 1e-3 })
    expect_error(both, ashlar.friction_demand, s, { method = "kinematic", bracket_tolerance = 1e-3, tolerance = 1e-3 })
    expect_error(both, ashlar.load_factor, s, { method = "kinematic", bracket_tolerance = 1e-3, tolerance = 1e-3 })
    expect_error(both, ashlar.geometric_factor, arch_of, 0.75, { bracket_tolerance = 1e-3, tolerance = 1e-3 })
    expect_error({ "bracket_tolerance: expected a number in (0, 1)" }, ashlar.friction_demand, s,
                 { bracket_tolerance = 2 })
    expect_error({ "bracket_tolerance: expected a number > 0" }, ashlar.geometric_factor, arch_of, 0.75,
                 { bracket_tolerance = 0 })
    expect_error({ "bracket_tolerance: only with method = \"kinematic\"" }, ashlar.load_factor, s,
                 { bracket_tolerance = 1e-3 })
    expect_error({ "tolerance: only with method = \"kinematic\"" }, ashlar.load_factor, s, { tolerance = 1e-3 })
  end)
end)

describe("the documented defaults", function()
  it("are what friction_demand does without the option, by either method", function()
    local default, kinematic = numbers_of(documented_defaults("### Friction demand").bracket_tolerance)
    assert.equal(1e-6, default)
    assert.equal(1e-3, kinematic)
    local s = arch_of(0.75)
    local implicit = ashlar.friction_demand(s)
    local explicit = ashlar.friction_demand(s, { bracket_tolerance = default })
    assert.equal(explicit.friction, implicit.friction)
    assert.equal(explicit.programs, implicit.programs)
    local incline = block_on_incline()
    local k_implicit = ashlar.friction_demand(incline, { method = "kinematic" })
    local k_explicit = ashlar.friction_demand(incline, { method = "kinematic", bracket_tolerance = kinematic })
    assert.equal(k_explicit.friction, k_implicit.friction)
    assert.equal(k_explicit.programs, k_implicit.programs)
  end)

  it("are what load_factor does without the option", function()
    local default = numbers_of(documented_defaults("### Load factor").bracket_tolerance)
    assert.equal(1e-3, default)
    local options = { friction = 0.5, method = "kinematic" }
    local implicit = ashlar.load_factor(squat_block(), options)
    options.bracket_tolerance = default
    local explicit = ashlar.load_factor(squat_block(), options)
    assert.equal(explicit.factor, implicit.factor)
    assert.equal(explicit.analyses, implicit.analyses)
  end)

  it("are what geometric_factor does without the options", function()
    local rows = documented_defaults("### Geometric factor of safety")
    local tolerance, most = numbers_of(rows.bracket_tolerance), numbers_of(rows.max_analyses)
    assert.equal(1e-6, tolerance)
    local implicit = ashlar.geometric_factor(arch_of, 0.75, { friction = math.huge })
    local explicit = ashlar.geometric_factor(arch_of, 0.75,
                                             { friction = math.huge, bracket_tolerance = tolerance, max_analyses = most })
    assert.equal(explicit.minimum, implicit.minimum)
    assert.equal(explicit.analyses, implicit.analyses)
  end)

  it("are what load_capacity and important_weights do without the options", function()
    local rows = documented_defaults("## Weights: sensitivity, load capacity, necessary and important weights")
    assert.equal("0", rows.threads)
    assert.equal("true", rows.symmetry)
    local arch = arch_of(0.75)
    arch:set_planar(false)  -- planar problems are not searched for symmetries
    local implicit = ashlar.load_capacity(arch, { progress = false })
    local explicit = ashlar.load_capacity(arch, { progress = false, threads = 0, symmetry = true })
    -- Workers take blocks as they come, so the last bits may differ.
    for i = 1, #arch do
      assert.equal(type(explicit[i]), type(implicit[i]), "block " .. i)
      if explicit[i] then
        for _, bound in ipairs{ "min", "max" } do
          local expected = explicit[i][bound]
          if expected == math.huge then
            assert.equal(expected, implicit[i][bound], bound .. " " .. i)
          else
            support.near(implicit[i][bound], expected, 1e-9 * math.max(1, expected), bound .. " " .. i)
          end
        end
      end
    end
    assert.equal(2, implicit.symmetries)  -- the arch's mirror: used by default
    assert.equal(1, ashlar.load_capacity(arch, { progress = false, symmetry = false }).symmetries)
    assert.equal(2, ashlar.important_weights(arch, { progress = false }).symmetries)
  end)
end)
