-- The generators' default discretisations: from the default count on, the
-- main question's answer stays within 1% of the converged one (the
-- measurement is scripts/model_discretisation.lua; here the default and
-- the next counts are checked, against Milankovitch's limit for the
-- semicircle and against a fine model for the others).
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"

local NO_SLIDING = { friction = math.huge }

local function within_one_percent(value, reference, what)
  local error = (value - reference) / reference
  assert(math.abs(error) <= 0.01, ("%s: %.6g is %+.2f%% from %.6g"):format(what, value, 100 * error, reference))
end

-- Minimum thickness without sliding of models.arch{ options, voussoirs = n },
-- below `standing` (default 0.8; a fine pointed arch needs a tighter
-- bracket, as its thick voussoirs next to the apex degenerate).
local function arch_minimum_thickness(options, n, standing)
  return support.threshold(function(t)
    local o = { voussoirs = n, thickness = t }
    for k, v in pairs(options) do o[k] = v end
    return ashlar.analyze(models.arch(o), NO_SLIDING).stable
  end, 0.02, standing or 0.8, 1e-5)
end

describe("default discretisations", function()
  it("semicircular arch: the default count and the next three within 1% of t/R = 0.1075", function()
    local default = #models.arch{} - 2
    assert.equal(24, default)
    for n = default, default + 3 do
      within_one_percent(arch_minimum_thickness({}, n) / 5, 0.1075, n .. " voussoirs")
    end
    -- The coarser 23 is not: a joint falls far from the hinge.
    assert.is_true(arch_minimum_thickness({}, 23) / 5 < 0.99 * 0.1075)
  end)

  for _, case in ipairs{ { shape = "pointed", fine = 256, step = 2, standing = 0.4 }, { shape = "segmental", fine = 512, step = 1 },
                          { shape = "elliptical", fine = 512, step = 1 } } do
    it(case.shape .. " arch: the default count and the next ones within 1% of a fine arch", function()
      local options = { shape = case.shape }
      local default = #models.arch(options) - 2
      local reference = arch_minimum_thickness(options, case.fine, case.standing)
      for n = default, default + 2 * case.step, case.step do
        within_one_percent(arch_minimum_thickness(options, n, case.standing), reference, case.shape .. " " .. n)
      end
    end)
  end

  it("dome: the default parallels and the next ones within 1% of 64 parallels", function()
    local function minimum_thickness(parallels)
      return support.threshold(function(t)
        return ashlar.analyze(models.dome{ parallels = parallels, thickness = t }).stable
      end, 0.1, 0.3, 1e-4)
    end
    local reference = minimum_thickness(64)
    -- 16 meridians x 18 parallels: 288 voussoirs, the keystone, 16 supports.
    assert.equal(16 * 18 + 1 + 16, #models.dome{})
    for _, parallels in ipairs{ 18, 20, 22 } do
      within_one_percent(minimum_thickness(parallels), reference, parallels .. " parallels")
    end
  end)
end)
