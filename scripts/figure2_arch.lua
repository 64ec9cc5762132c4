-- Figure 2 of Shin 2014: an unstable arch made stable by moving its vertices
-- down the structural gradient, with steepest descent and with L-BFGS.
--   ashlar scripts/figure2_arch.lua [output folder, default "docs/figures/optimisation"]
-- Writes figure2_arch.csv (infeasibility per iteration and method), a chart
-- figure2_arch.png / .svg, and the arch before and after (L-BFGS) as .glb,
-- coloured by the tension each block needs. Prints iterations, analyses and
-- time to stable per method.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"

local folder = arg[1] or "docs/figures/optimisation"
os.execute("mkdir -p " .. script_support.shell_quoted(folder))

-- A semicircular arch of 24 voussoirs at 3/4 of its minimum thickness
-- (0.5355 m for R = 5 m without sliding, 24 voussoirs): unstable.
local arch = models.arch{ radius = 5, thickness = 0.4, voussoirs = 24 }
local analysis = { friction = math.huge }
local options = {
  analysis = analysis,
  max_iterations = 40,
  initial_step = 0.01,  -- m: the first step moves no vertex further
  symmetry = { point = { 0, 0, 0 }, normal = { 1, 0, 0 } },  -- the arch stays symmetric
}

local rows = { "method,iteration,infeasibility,penalty,step_m,seconds" }
local results = {}
for _, method in ipairs{ "gradient", "lbfgs" } do
  options.method = method
  local r = ashlar.optimize(arch, options)
  results[method] = r
  for _, h in ipairs(r.history) do
    rows[#rows + 1] = ("%s,%d,%.9g,%.9g,%.6g,%.6f"):format(method, h.iteration, h.infeasibility,
      h.penalty, h.step, h.seconds)
  end
  local last = r.history[#r.history]
  print(("%-8s %s after %d iterations, %d analyses with gradient, %.3f s (%s)"):format(method,
    r.stable and "stable" or "NOT stable", last.iteration, r.evaluations, last.seconds, r.status))
end
script_support.write_atomically(folder .. "/figure2_arch.csv", table.concat(rows, "\n") .. "\n")

local function export(s, name)
  local r = ashlar.analyze(s, analysis)
  local tension = {}
  for i = 1, #s do tension[i] = r.blocks[i].tension end
  ashlar.export(s, folder .. "/" .. name, { result = r, forces = true,
    color = { values = tension, map = "magma", range = { 0, 5e4 } } })
end
export(arch, "figure2_arch_before.glb")
export(results.lbfgs.structure, "figure2_arch_after.glb")

-- The chart from the CSV: one line per method, named in the legend.
local NAMES = { gradient = "gradient descent", lbfgs = "L-BFGS" }
local points = {}
for _, row in ipairs(script_support.read_csv(folder .. "/figure2_arch.csv")) do
  points[#points + 1] = { iteration = row.iteration, [NAMES[row.method]] = row.infeasibility }
end
script_support.chart(folder .. "/figure2_arch", { data = points, x = "iteration", y = { NAMES.gradient, NAMES.lbfgs },
  title = "Unstable arch made stable (R = 5 m, t = 0.4 m, 24 voussoirs, no sliding)",
  y_label = "infeasibility (tension / weight)" })
