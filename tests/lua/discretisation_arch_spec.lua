-- The arch generator's default discretisations: from the default count on,
-- the minimum thickness without sliding stays within 1% of the converged one
-- (the measurement is scripts/model_discretisation.lua; here the default and
-- the next counts are checked, against Milankovitch's limit for the
-- semicircle and against a fine arch for the other shapes). The dome's are
-- in discretisation_dome_spec.lua, a test of its own that runs beside this.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"

local NO_SLIDING = { friction = math.huge }

-- Whether models.arch{ options, voussoirs = n, thickness = t } stands
-- without sliding, as a function of t.
local function stands_at(options, n)
  return function(t)
    local o = { voussoirs = n, thickness = t }
    for k, v in pairs(options) do o[k] = v end
    return ashlar.analyze(models.arch(o), NO_SLIDING).stable
  end
end

-- Brackets of the minimum thickness: it lies below STANDING (a fine pointed
-- arch needs a tighter one, as its thick voussoirs next to the apex
-- degenerate).
local FAILING, STANDING = 0.02, 0.8

describe("arch default discretisations", function()
  it("semicircular: the default count and the next three within 1% of t/R = 0.1075", function()
    local default = #models.arch{} - 2
    assert.equal(24, default)
    -- radius 5: t = 0.1075 × 5
    local limit = 0.1075 * 5
    for n = default, default + 3 do
      support.threshold_within(stands_at({}, n), limit, 0.01, n .. " voussoirs", FAILING, STANDING)
    end
    -- The coarser 23 is not: a joint falls far from the hinge, and it stands
    -- 1% below the limit.
    assert.is_true(stands_at({}, 23)(0.99 * limit))
  end)

  -- Release suite only (the fine arches' bisections, 21 s under the
  -- sanitizers): the claim is numerical, and arch_shapes_spec builds and
  -- analyses these shapes under them.
  for _, case in ipairs{ { shape = "pointed", fine = 256, step = 2, standing = 0.4 }, { shape = "segmental", fine = 512, step = 1 },
                          { shape = "elliptical", fine = 512, step = 1 } } do
    it(case.shape .. ": the default count and the next ones within 1% of a fine arch #unsanitized", function()
      local options = { shape = case.shape }
      local standing = case.standing or STANDING
      local default = #models.arch(options) - 2
      local reference = support.threshold(stands_at(options, case.fine), FAILING, standing, 1e-5)
      for n = default, default + 2 * case.step, case.step do
        support.threshold_within(stands_at(options, n), reference, 0.01, case.shape .. " " .. n, FAILING, standing)
      end
    end)
  end
end)
