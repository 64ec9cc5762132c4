-- A vault that was built and stood: the Armadillo (Block Research Group,
-- 2016; tests/data/compas_cra/armadillo_cra.json, from compas_cra's
-- samples): 399 voussoirs, 33 of them supports, faces warped by up to
-- 3.8 cm, joints as narrow as 5.5 cm, gaps under a millimetre. Its contacts
-- must not depend on the tolerance or on how it is turned, and its verdict
-- is checked against an LP that shares no code with ashlar
-- (tests/tools/equilibrium_lp.py, HiGHS).
local ashlar = require "ashlar"
local support = require "spec_support"

local near = support.near
local PATH = "../data/compas_cra/armadillo_cra.json"  -- specs run in tests/lua
local FRICTION = 0.84

local function vault(stored)
  return ashlar.import(PATH, { planarity = 0.05, interfaces = stored and "file" or "detect" })
end

describe("the Armadillo vault", function()
  local s
  setup(function() s = vault() end)

  it("keeps all 1,043 contacts at every tolerance from 1 to 6 cm, refuses no overlap, and stands", function()
    assert.are.equal(399, #s)
    for _, tolerance in ipairs{ 0.01, 0.02, 0.03, 0.04, 0.05, 0.06 } do
      assert.are.equal(1043, #s:interfaces{ tolerance = tolerance }, "tolerance " .. tolerance)
      assert.are.equal(0, #s:overlaps{ tolerance = tolerance }, "tolerance " .. tolerance)
      local r = ashlar.analyze(s, { friction = FRICTION, contact_tolerance = tolerance })
      assert.is_true(r.stable, ("tolerance %g: %s"):format(tolerance, tostring(r)))
    end
  end)

  it("finds the same contacts turned about any axis and moved", function()
    local reference = s:interfaces{ tolerance = 0.04 }
    local area = 0
    for _, f in ipairs(reference) do area = area + f.area end
    for _, motion in ipairs{ { { 0, 0, 1 }, 0.8 }, { { 1, 2, 3 }, 2.1 } } do
      local turned = ashlar.structure()
      for i = 1, #s do
        turned:add(s:block(i):rotated(motion[1], motion[2], { 16, 4, 0 }):translated{ 3, -2, 1 },
          { support = s:is_support(i) })
      end
      local found = turned:interfaces{ tolerance = 0.04 }
      assert.are.equal(#reference, #found)
      local turned_area = 0
      for k, f in ipairs(found) do
        assert.are.equal(reference[k].a, f.a)
        assert.are.equal(reference[k].b, f.b)
        turned_area = turned_area + f.area
      end
      near(turned_area, area, 1e-9 * area, "total contact area")
    end
  end)

  it("stands as an independent LP finds on the same contacts, whose supports carry its weight", function()
    local stands, infeasibility = support.independent_verdict(s, FRICTION, { tolerance = 0.04 })
    assert.is_true(stands, "the LP needs slack " .. infeasibility)
    local r = ashlar.analyze(s, { friction = FRICTION, contact_tolerance = 0.04 })
    local contacts = s:interfaces{ tolerance = 0.04 }
    local weight, carried = 0, 0
    for i = 1, #s do
      if not s:is_support(i) then weight = weight + 9.81 * s:block(i):mass() end
    end
    for k, f in ipairs(r.interfaces) do
      -- The force on b is the resultant; on a support the reaction is its opposite.
      local a_support, b_support = s:is_support(contacts[k].a), s:is_support(contacts[k].b)
      if a_support and not b_support then carried = carried + f.resultant[3] end
      if b_support and not a_support then carried = carried - f.resultant[3] end
    end
    near(carried, weight, 1e-6 * weight, "vertical reactions against the weight")
  end)

  it("stands on the interfaces the file stores too", function()
    local stored = vault(true)
    assert.are.equal(1019, #stored:interfaces())
    local r = ashlar.analyze(stored, { friction = FRICTION, contact_tolerance = 0.04 })
    assert.is_true(r.stable, tostring(r))
  end)
end)
