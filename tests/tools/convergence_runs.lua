-- The simulations whose contact solves were measured for convergence
-- (docs/performance.md, "Convergence of the contact solves"): a line per
-- run with its steps, unconverged steps, largest residual and when,
-- sweeps and global steps a step, seconds, largest displacement.
-- Run from the repository's root:
--   ashlar tests/tools/convergence_runs.lua vault
--     the Armadillo's dynamics as compare_methods_vault_spec runs it
--     (399 blocks, about 4,700 contact points, 50 steps of 1 ms)
--   ashlar tests/tools/convergence_runs.lua arches [k]
--     six semicircular arches collapsing (radius 5, friction 0.7): 16, 18,
--     20, 22 and 24 voussoirs 0.45 thick for 1.5 s, 22 voussoirs 0.40
--     thick for 1.2 s; k: the k-th alone. Each is run again up to its
--     collapse (sim:summary().collapse_time, the first block's fall), for
--     the steps of the structure's own motion apart from the debris's
local ashlar = require "ashlar"
local models = require "ashlar.models"

local function line(name, sim)
  return ("%s: steps %d unconverged %d split %d max_residual %.3g m/s at %s s, %.1f sweeps and %.2f global steps a step, "
    .. "%.2f s, largest displacement %.6g m"):format(name, sim.steps, sim.unconverged_steps, sim.split_steps, sim.max_residual,
    tostring(sim.max_residual_time), sim.sweeps / sim.steps, sim.global_steps / sim.steps, sim.seconds,
    sim.max_displacement)
end

local which = arg[1]
if which == "vault" then
  local s = ashlar.import("tests/data/compas_cra/armadillo_cra.json", { planarity = 0.05, interfaces = "detect" })
  print(line("vault", ashlar.simulate(s, { duration = 0.05, friction = 0.5, contact_tolerance = 0.03 })))
elseif which == "arches" then
  local only = tonumber(arg[2])
  local cases = { { 16, 0.45, 1.5 }, { 18, 0.45, 1.5 }, { 20, 0.45, 1.5 }, { 22, 0.45, 1.5 }, { 24, 0.45, 1.5 },
                  { 22, 0.40, 1.2 } }
  local unconverged, seconds, before_collapse = 0, 0, 0
  for k, c in ipairs(cases) do
    if not only or only == k then
      local arch = models.arch{ radius = 5, thickness = c[2], voussoirs = c[1] }
      local sim = ashlar.simulate(arch, { duration = c[3], friction = 0.7 })
      unconverged, seconds = unconverged + sim.unconverged_steps, seconds + sim.seconds
      print(line(("arch of %d voussoirs, %.2f thick"):format(c[1], c[2]), sim))
      local collapse = sim:summary().collapse_time
      if collapse then
        local standing = ashlar.simulate(arch, { duration = collapse, friction = 0.7 })
        before_collapse = before_collapse + standing.unconverged_steps
        print(line(("  up to its collapse at %.3f s"):format(collapse), standing))
      end
    end
  end
  print(("all: %d unconverged steps (%d before the collapses), %.1f s"):format(unconverged, before_collapse, seconds))
else
  error("usage: ashlar tests/tools/convergence_runs.lua vault | arches [k]")
end
