-- FEA accuracy and cost, printed (and written as CSV beside the charts):
--   ashlar scripts/bench_fea.lua [folder]     (default docs/figures)
-- 1. A cantilever of ten 0.2 m cubes clamped to a wall, under its weight:
--    tip deflection against Timoshenko beam theory as `refine` grows, and
--    the observed order of convergence.
-- 2. FEA time and peak memory (resident set, ashlar.memory) for about
--    1,000 and 10,000 elements: an arch refined, with relaxation.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local folder = arg[1] or "docs/figures"
support.make_folders(folder)

local E, RHO, G = 20e9, 2400, 9.81
local SIDE, COUNT = 0.2, 10
local LENGTH = SIDE * COUNT

local beam = ashlar.structure()
beam:add(ashlar.box{ size = { 1, 1, 1 }, center = { -0.5, 0, 0.5 } }, { support = true, name = "wall" })
for k = 1, COUNT do
  beam:add(ashlar.box{ size = { SIDE, SIDE, SIDE }, center = { SIDE * (k - 0.5), 0, 0.5 } })
end
-- Poisson 0: the beam theory's assumptions; kappa = 5/6, G = E/2.
local q, inertia = RHO * G * SIDE * SIDE, SIDE ^ 4 / 12
local reference = q * LENGTH ^ 4 / (8 * E * inertia) + q * LENGTH ^ 2 / (2 * (5 / 6) * (E / 2) * SIDE * SIDE)

print(("Cantilever %g m of %d cubes (%g m), E = %g Pa, poisson 0; Timoshenko tip deflection %.6e m"):format(
  LENGTH, COUNT, SIDE, E, reference))
print("| refine | elements | tip deflection (m) | relative error | order | time |")
print("|---|---|---|---|---|---|")
local rows, previous = { "refine,elements,tip,relative_error,seconds" }, nil
for _, refine in ipairs{ 1, 2, 4, 8 } do
  local start = ashlar.clock()
  local fe = ashlar.fea(beam, { refine = refine, poisson = 0, relax = false })
  local seconds = ashlar.clock() - start
  local tip, n = 0, 0
  for i, p in ipairs(fe.nodes) do
    if math.abs(p[1] - LENGTH) < 1e-9 then tip, n = tip - fe.displacements[i][3], n + 1 end
  end
  tip = tip / n
  local err = math.abs(tip - reference) / reference
  local order = previous and ("%.2f"):format(math.log(previous / err, 2)) or ""
  print(("| %d | %d | %.6e | %.4f | %s | %.3f s |"):format(refine, fe.element_count, tip, err, order, seconds))
  rows[#rows + 1] = ("%d,%d,%.9e,%.6e,%.4f"):format(refine, fe.element_count, tip, err, seconds)
  previous = err
end
support.write_atomically(folder .. "/fea_cantilever.csv", table.concat(rows, "\n") .. "\n")

print("\nFEA cost (arch R = 5 m, t = 0.6 m, with relaxation, release = largest)")
print("| elements | dofs | contact nodes | factor nonzeros | solves | time | peak memory |")
print("|---|---|---|---|---|---|---|")
local cost = { "elements,dofs,contacts,factor_nonzeros,solves,seconds,peak_mb" }
for _, case in ipairs{ { voussoirs = 8, refine = 5 }, { voussoirs = 10, refine = 10 } } do
  local s = models.arch{ radius = 5, thickness = 0.6, voussoirs = case.voussoirs }
  collectgarbage()
  ashlar.memory{ reset_peak = true }
  local before = ashlar.memory().resident_mb
  local start = ashlar.clock()
  local fe = ashlar.fea(s, { refine = case.refine, release = "largest" })
  local seconds = ashlar.clock() - start
  local peak = ashlar.memory().peak_mb
  print(("| %d | %d | %d | %.3g | %d | %.2f s | %.0f MB (%.0f MB before) |"):format(fe.element_count, fe.dofs,
    #fe.contacts, fe.factor_nonzeros, #fe.history, seconds, peak, before))
  cost[#cost + 1] = ("%d,%d,%d,%.0f,%d,%.4f,%.1f"):format(fe.element_count, fe.dofs, #fe.contacts,
    fe.factor_nonzeros, #fe.history, seconds, peak)
end
support.write_atomically(folder .. "/fea_cost.csv", table.concat(cost, "\n") .. "\n")
