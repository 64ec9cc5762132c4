-- The arbiter (ashlar.compare_methods) on a built vault: the Armadillo
-- (tests/data/compas_cra), where below mu 0.68 the kinematic method lets a
-- voussoir fall and the dynamics from rest decides. 12 s in Release, 256 s
-- under the sanitizers (the kinematic rounds and the dynamics, on 399
-- blocks): it runs in the Release suite only; compare_methods_spec checks
-- the same code paths on small structures under the sanitizers.
local ashlar = require "ashlar"

describe("the arbiter on a built vault", function()
  it("finds the Armadillo standing at mu 0.5 by the dynamics, where the kinematic method lets a voussoir fall", function()
    -- 399 voussoirs (33 supports), warped faces; it was built and stood, and
    -- an independent LP finds it standing (real_vault_spec). Below mu 0.68
    -- the kinematic rounds let voussoir C-11-1 fall alone (its fixed point
    -- from no prestress); from rest under gravity no vertex moves.
    local s = ashlar.import("../data/compas_cra/armadillo_cra.json", { planarity = 0.05, interfaces = "detect" })
    local c = ashlar.compare_methods(s, { friction = 0.5, contact_tolerance = 0.03, margin = false,
                                          dynamics = { duration = 0.05 } })
    assert.equal("stands", c.verdict, c.reason)
    assert.equal("dynamics", c.decided_by)
    assert.equal("stands", c.methods.equilibrium)
    assert.equal("falls", c.methods.kinematic)
    assert.equal("stands", c.methods.dynamics)
    -- The dynamics' resolution: no vertex moves a micrometre (the solver's
    -- drift is about 1e-4 g h per step).
    assert.is_true(c.displacement < 1e-5, tostring(c.displacement))
  end)

  it("solves every one of the dynamics' steps of 4,700 contact points", function()
    -- The arbiter's run, alone. Sweeps alone stopped at max_sweeps on 4 of
    -- the 50 steps (101 sweeps a step); with Newton's method on the rows
    -- that stall, on the first (from zero impulses, 1.4e-5 m/s, 34 sweeps
    -- a step); with rows within a tenth of the tolerance left as they are
    -- (contact_solver.hpp), on none, in 17 sweeps a step.
    local s = ashlar.import("../data/compas_cra/armadillo_cra.json", { planarity = 0.05, interfaces = "detect" })
    local sim = ashlar.simulate(s, { duration = 0.05, friction = 0.5, contact_tolerance = 0.03 })
    assert.equal(50, sim.steps)
    assert.equal(0, sim.unconverged_steps)
    -- Every step's residual within the solver's tolerance (1e-4 g h).
    assert.is_true(sim.max_residual <= 1e-4 * 9.81 * 1e-3, tostring(sim.max_residual))
    assert.is_true(sim.sweeps / sim.steps < 30, tostring(sim.sweeps / sim.steps))
    assert.is_true(sim.max_displacement < 1e-5, tostring(sim.max_displacement))
  end)
end)
