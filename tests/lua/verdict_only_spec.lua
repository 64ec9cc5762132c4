-- ashlar.analyze{ verdict_only = true }: the solve stops at the first forces
-- that prove stability. Those forces are checked here by statics alone:
-- every free block's interface forces balance its weight (force and moment)
-- with no tension anywhere.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"

local G = 9.81

describe("ashlar.analyze with verdict_only", function()
  local cases = {
    { name = "a 31-voussoir arch, t / R = 0.12", build = function()
      return models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 } end },
    { name = "a 16 x 18 dome", build = function() return models.dome{} end },
    { name = "a running-bond wall solved in 3D", build = function()
      local s = models.wall{ length = 2.4, height = 0.7 }
      s:set_planar(false)
      return s
    end },
  }
  for _, case in ipairs(cases) do
    it("certifies " .. case.name .. " in fewer iterations, with forces that balance every block", function()
      local s = case.build()
      local full = ashlar.analyze(s)
      local r = ashlar.analyze(s, { verdict_only = true })
      assert.equal("converged", full.status)
      assert.is_true(full.stable)
      assert.equal("certified", r.status)
      assert.is_true(r.stable)
      assert.equal(0, r.infeasibility)
      assert.is_true(r.iterations < full.iterations, ("%d iterations, %d to the optimum"):format(r.iterations,
        full.iterations))
      local weight = 0
      for i = 1, #s do
        if not s:is_support(i) then weight = math.max(weight, G * s:block(i):mass()) end
      end
      local force, moment, tension = support.statics(s, r)
      -- stable_tolerance (1e-6) of the largest block weight, and its moment
      -- over a metre-sized block.
      assert(force <= 1e-6 * weight, ("force imbalance %g N of a block weight %g N"):format(force, weight))
      assert(moment <= 1e-6 * weight * 2, ("moment imbalance %g N m"):format(moment))
      assert(tension <= 1e-6 * weight, ("tension %g N"):format(tension))
    end)
  end

  it("solves an unstable structure to the optimum, as without it", function()
    local s = models.arch{ radius = 5, thickness = 0.5, voussoirs = 24 }
    local full = ashlar.analyze(s)
    local r = ashlar.analyze(s, { verdict_only = true })
    assert.equal("converged", r.status)
    assert.is_false(r.stable)
    assert.equal(full.iterations, r.iterations)
    assert.near(full.infeasibility, r.infeasibility, 1e-12 * full.infeasibility)
  end)

  it("gives the verdict of the full solve on both sides of the minimum thickness", function()
    -- 16 polyhedral voussoirs: t / R = 0.10708 (docs, Verification).
    for _, ratio in ipairs{ 0.104, 0.106, 0.108, 0.110 } do
      local s = models.arch{ radius = 5, thickness = 5 * ratio, voussoirs = 16 }
      local full = ashlar.analyze(s, { friction = math.huge })
      local r = ashlar.analyze(s, { friction = math.huge, verdict_only = true })
      assert.equal(ratio > 0.10708, full.stable, "t/R " .. ratio)
      assert.equal(full.stable, r.stable, "t/R " .. ratio)
    end
  end)

  it("is refused unless a boolean", function()
    local s = models.arch{ radius = 5, thickness = 0.6, voussoirs = 8 }
    local ok, message = pcall(ashlar.analyze, s, { verdict_only = 1 })
    assert.is_false(ok)
    assert.matches("verdict_only", message)
  end)
end)
