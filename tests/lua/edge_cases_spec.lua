-- "Where methods fail": structures at the edge of standing (arches at their
-- minimum thickness, stacks at the tipping point, a block on an incline at
-- the friction angle, nearly coplanar and barely touching contacts, extreme
-- aspect ratios, 1e-3 and 1e3 scale). ashlar.analyze, ashlar.load_factor
-- and ashlar.friction_demand must each give the right answer or say that
-- they cannot: never a wrong confident answer. The cases and their
-- independent references are in edge_cases.lua, shared with
-- scripts/edge_cases.lua, which prints the pass table.
local ashlar = require "ashlar"
local edges = require "edge_cases"

local function expect_pass(row)
  assert(row.pass, edges.describe(row))
end

describe("edge cases", function()
  local cases = edges.cases()
  for _, case in ipairs(cases) do
    it(case.name, function() expect_pass(edges.run(case)) end)
  end

  it("gives the same answers at scales 1e-3, 1 and 1e3", function()
    for _, row in ipairs(edges.scale_rows(cases)) do expect_pass(row) end
  end)

  it("finds the arch's threshold alike by the thrust line, load_factor's root and analyze's bisection", function()
    expect_pass(edges.threshold_row(24))
    expect_pass(edges.threshold_row(16))
  end)

  it("finds the arch's minimum thickness ratio alike at scales 1e-3, 1 and 1e3", function()
    expect_pass(edges.scale_threshold_row())
  end)

  it("finds the arch's minimum thickness with ashlar.geometric_factor alike at every scale", function()
    expect_pass(edges.geometric_factor_row())
  end)

  it("agrees with Heyman's t/R = 0.1075 for a fine arch", function()
    expect_pass(edges.heyman_row())
  end)

  it("analyses a dome alike at scales 1e-3, 1 and 1e3", function()
    for _, row in ipairs(edges.dome_rows()) do expect_pass(row) end
  end)

  it("flags a stable verdict that holds only within stable_tolerance as borderline", function()
    -- A block past its support's edge by 1e-7 of its width needs a tension
    -- of about 5e-8 of its weight: stable to the tolerance, and flagged.
    local past = ashlar.analyze(edges.family.stack.build(1e-7, 1))
    assert.is_true(past.stable)
    assert.is_true(past.borderline)
    -- Well inside, or well past, the verdict is clear.
    assert.is_false(ashlar.analyze(edges.family.stack.build(-1e-2, 1)).borderline)
    assert.is_false(ashlar.analyze(edges.family.stack.build(1e-2, 1)).borderline)
    -- The band follows stable_tolerance.
    assert.is_false(ashlar.analyze(edges.family.stack.build(1e-7, 1), { stable_tolerance = 1e-9 }).stable)
  end)
end)
