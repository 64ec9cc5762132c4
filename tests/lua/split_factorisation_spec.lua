-- Large analyses factor their normal matrix on two cores, split around a
-- separator (SparseCholesky, from 2,000 rows). Checked against a solve
-- that is not split and against statics: a running-bond wall of 22 x 22
-- bricks (496 blocks) has 2,976 rows solved in 3D (split) and 1,488 rows
-- solved as a planar problem (whole); both are the same optimisation
-- problem, since the wall is loaded in its plane.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local function wall(planar)
  local s = models.wall{ length = 22 * 0.24, height = 22 * 0.07 }
  if not planar then s:set_planar(false) end
  return s
end

describe("a split factorisation", function()
  it("solves a 3D wall to the planar solve's optimum, with forces that balance every block", function()
    local s = wall(false)
    local planar = ashlar.analyze(wall(true), { friction = 0.7 })
    local r = ashlar.analyze(s, { friction = 0.7 })
    assert.equal("converged", planar.status)
    assert.equal("converged", r.status)
    assert.is_true(r.stable)
    assert.near(planar.objective, r.objective, 1e-8 * math.abs(planar.objective))
    local weight = 0
    for i = 1, #s do
      if not s:is_support(i) then weight = math.max(weight, 9.81 * s:block(i):mass()) end
    end
    local force, moment, tension = support.statics(s, r)
    assert(force <= 1e-6 * weight, ("force imbalance %g N of a block weight %g N"):format(force, weight))
    assert(moment <= 1e-6 * weight, ("moment imbalance %g N m"):format(moment))
    assert(tension <= 1e-6 * weight, ("tension %g N"):format(tension))
  end)

  it("gives the planar solve's infeasibility for a wall pushed over", function()
    local pushed = support.push_laterally(wall(false), 1.0)
    local planar = ashlar.analyze(support.push_laterally(wall(true), 1.0), { friction = 0.7 })
    local r = ashlar.analyze(pushed, { friction = 0.7 })
    assert.equal("converged", planar.status)
    assert.equal("converged", r.status)
    assert.is_false(r.stable)
    assert.is_true(planar.infeasibility > 0)
    assert.near(planar.infeasibility, r.infeasibility, 1e-6 * planar.infeasibility)
  end)
end)
