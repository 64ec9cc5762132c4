-- The dome generator's default discretisation: from the default parallels
-- on, the minimum thickness stays within 1% of a fine dome's (64 parallels;
-- the measurement is scripts/model_discretisation.lua). Apart from the
-- arches' (discretisation_arch_spec.lua) because the fine dome is the
-- suite's longest single check, and so runs beside the rest.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"

local function stands_at(parallels)
  return function(t)
    return ashlar.analyze(models.dome{ parallels = parallels, thickness = t }).stable
  end
end

-- Brackets of the minimum thickness (m) of the default dome, radius 5 m.
local FAILING, STANDING = 0.1, 0.3

describe("dome default discretisation", function()
  it("the default parallels and the next ones within 1% of 64 parallels", function()
    local reference = support.threshold(stands_at(64), FAILING, STANDING, 1e-4)
    -- 16 meridians x 18 parallels: 288 voussoirs, the keystone, 16 supports.
    assert.equal(16 * 18 + 1 + 16, #models.dome{})
    for _, parallels in ipairs{ 18, 20, 22 } do
      support.threshold_within(stands_at(parallels), reference, 0.01, parallels .. " parallels", FAILING, STANDING)
    end
  end)
end)
