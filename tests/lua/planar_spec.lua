-- Planar models: the 3-equation solve (Fx, Fz, My per block) gives the same
-- answer as the general 6-equation one, standing or falling: stability,
-- infeasibility and the resultant normal force on every interface.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near = support.near

local CASES = {
  { "arch that stands", function() return models.arch{} end, math.huge },
  { "arch too thin to stand", function() return models.arch{ thickness = 0.4 } end, math.huge },
  { "pointed arch, friction 0.7", function() return models.arch{ shape = "pointed", thickness = 0.4 } end, 0.7 },
  { "wall", function() return models.wall{ length = 1.2, height = 0.35 } end, 0.7 },
  { "flying buttress without pinnacle", function() return models.flying_buttress{ pinnacle_height = 0 } end, 0.7 },
  { "overhanging stack", function() return models.stack{ blocks = 4, offset = 0.4 } end, 0.7 },
}

describe("planar solve", function()
  for _, case in ipairs(CASES) do
    local name, build, friction = case[1], case[2], case[3]
    it(name .. ": the same answer with 3 and 6 equations per block", function()
      local s = build()
      assert.is_true(s:is_planar())
      local planar = ashlar.analyze(s, { friction = friction })
      s:set_planar(false)
      local spatial = ashlar.analyze(s, { friction = friction })
      assert.equal(spatial.stable, planar.stable)
      near(planar.infeasibility, spatial.infeasibility, 1e-6 * (1 + spatial.infeasibility), "infeasibility")
      -- The optimum is unique, but the solves stop at a duality gap of
      -- 1e-10 (scaled) and the objective only regularises the statically
      -- indeterminate forces (1e-4 / n per squared unit of force): a force
      -- the structure does not need is known to sqrt(2e-10 n / 1e-4) mean
      -- block weights: 7.3e-3 of 40 N on the wall's 27 free blocks, 0.3 N,
      -- 1.4e-3 of its largest joint force (217 N). Compare relative to the
      -- largest one.
      local largest = 0
      for _, interface in ipairs(spatial.interfaces) do
        largest = math.max(largest, math.abs(interface.normal_force))
      end
      for k, interface in ipairs(spatial.interfaces) do
        near(planar.interfaces[k].normal_force, interface.normal_force, 2e-3 * largest, "interface " .. k)
      end
    end)
  end
end)
