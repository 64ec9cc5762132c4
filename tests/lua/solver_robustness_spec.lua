-- The equilibrium solve converges whatever the friction, and its optimum
-- behaves as the physics says: a larger friction coefficient only enlarges
-- the set of admissible forces, so the optimal penalty cannot grow with mu,
-- and a friction of 1e4 lets no arch joint slide, as math.huge does.
-- (The optimum itself is checked against cvxopt in qps_spec.)
local ashlar = require "ashlar"
local models = require "ashlar.models"

local FRICTIONS = { 0.1, 0.2, 0.3, 0.5, 0.7, 1, 10, 100, 1e4, math.huge }

describe("the equilibrium solve over friction", function()
  for _, t in ipairs{ 0.3, 0.5, 0.7, 0.9 } do
    describe(("on an arch R = 5 m, t = %g m, 24 voussoirs"):format(t), function()
      local results = {}
      setup(function()
        local s = models.arch{ radius = 5, thickness = t, voussoirs = 24 }
        for i, mu in ipairs(FRICTIONS) do results[i] = ashlar.analyze(s, { friction = mu }) end
      end)

      it("converges at every friction, with a non-negative infeasibility", function()
        for i, r in ipairs(results) do
          assert.equal("converged", r.status, "friction " .. FRICTIONS[i])
          assert(r.infeasibility >= 0, ("friction %g: infeasibility %g"):format(FRICTIONS[i], r.infeasibility))
        end
      end)

      it("needs no more tension as friction grows", function()
        for i = 2, #results do
          local before, now = results[i - 1].penalty, results[i].penalty
          assert(now <= before * (1 + 1e-7) + 1e-12,
            ("penalty %.10g at friction %g after %.10g at %g"):format(now, FRICTIONS[i], before, FRICTIONS[i - 1]))
        end
      end)

      -- Not exactly: without friction bound a vertex with no compression may
      -- still carry shear, which mu = 1e4 allows only up to 1e4 c, so the
      -- optima differ by O(1 / mu) (1.2e-5 relative at t = 0.5 m).
      it("treats friction 1e4 as no sliding, to 1e-4", function()
        local large, huge = results[#results - 1], results[#results]
        assert.equal(huge.stable, large.stable)
        assert(huge.penalty <= large.penalty * (1 + 1e-7) and large.penalty - huge.penalty <= 1e-4 * huge.penalty,
          ("penalty %.10g at 1e4, %.10g without sliding"):format(large.penalty, huge.penalty))
      end)
    end)
  end

  it("converges on a running-bond wall pushed sideways by 0.1 g at every friction", function()
    local s = models.wall{ length = 12 * 0.24, height = 6 * 0.07 }
    s:set_planar(false)
    for i = 1, #s do
      if not s:is_support(i) then
        local b = s:block(i)
        s:add_load{ block = i, force = { 0.1 * 9.81 * b:mass(), 0, 0 }, at = b:centroid() }
      end
    end
    for _, mu in ipairs(FRICTIONS) do
      local r = ashlar.analyze(s, { friction = mu })
      assert.equal("converged", r.status, "friction " .. mu)
      -- Each course must pass 0.1 of the weight above it sideways through
      -- its bed joints: friction 0.1 is just enough (the stack of courses
      -- has no other horizontal path), anything above it leaves room.
      if mu > 0.1 then assert.is_true(r.stable, "friction " .. mu) end
    end
  end)

  it("converges on running-bond walls pushed by 1 g, which must slide at friction 0.7", function()
    -- Infeasible, with tension unknowns carrying force: the dual residual
    -- used to stall near 1e-9 (inaccurate after 33-40 iterations). The
    -- planar and the 3D formulation of each wall are the same problem.
    local support = require "spec_support"
    for _, bricks in ipairs{ 10, 15, 26 } do
      local function pushed(planar)
        local s = models.wall{ length = bricks * 0.24, height = bricks * 0.07 }
        if not planar then s:set_planar(false) end
        return support.push_laterally(s, 1.0)
      end
      local planar = ashlar.analyze(pushed(true), { friction = 0.7 })
      local r = ashlar.analyze(pushed(false), { friction = 0.7 })
      assert.equal("converged", planar.status, bricks .. " bricks, planar")
      assert.equal("converged", r.status, bricks .. " bricks, 3D")
      assert.is_false(r.stable)
      assert.near(planar.infeasibility, r.infeasibility, 1e-8 * planar.infeasibility)
    end
  end)
end)
