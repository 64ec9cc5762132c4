-- Robustness of the equilibrium solve over friction and geometry: how many
-- analyses end converged, and whether the infeasibility is ever negative or
-- jumps where its neighbours do not.
--   ashlar scripts/solver_robustness.lua [output folder]
-- Three sweeps, each thickness (or load) x friction:
--   arch:  models.arch{ radius = 5, voussoirs = 24 }, t = 0.3 .. 0.9 m (25 values)
--   dome:  models.dome{ meridians = 16, parallels = 18 }, thickness 0.15 .. 0.6 m (10 values)
--   wall:  a running-bond wall pushed sideways (+x) by 0.1 g, 3D solve, 5 heights
-- friction in {0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 1, 10, 100, 1e4, math.huge}.
-- Prints the count of each status per sweep, every negative infeasibility
-- and every analysis that failed where a neighbour converged, and writes
-- solver_robustness.csv and a chart of infeasibility against friction (60
-- values from 0.05 to 1e4, and math.huge as a dashed line) for the arch at
-- t = 0.3 m (solver_robustness_mu.png/.svg).
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local folder = arg[1] or "."
support.make_folders(folder)

local FRICTIONS = { 0.1, 0.2, 0.3, 0.4, 0.5, 0.7, 1, 10, 100, 1e4, math.huge }

local function linspace(a, b, n)
  local values = {}
  for i = 0, n - 1 do values[#values + 1] = a + (b - a) * i / (n - 1) end
  return values
end

-- A wall pushed along its length by `g_fraction` of each brick's weight.
local function pushed_wall(courses, g_fraction)
  local s = models.wall{ length = 12 * 0.24, height = courses * 0.07 }
  s:set_planar(false)
  for i = 1, #s do
    local b = s:block(i)
    if not s:is_support(i) then
      s:add_load{ block = i, force = { g_fraction * 9.81 * b:mass(), 0, 0 }, at = b:centroid() }
    end
  end
  return s
end

local SWEEPS = {
  { name = "arch", values = linspace(0.3, 0.9, 25),
    build = function(t) return models.arch{ radius = 5, thickness = t, voussoirs = 24 } end },
  { name = "dome", values = linspace(0.15, 0.6, 10),
    build = function(t) return models.dome{ radius = 5, thickness = t, meridians = 16, parallels = 18 } end },
  { name = "wall", values = { 2, 4, 6, 8, 10 },
    build = function(courses) return pushed_wall(courses, 0.1) end },
}

local csv = { "sweep,value,friction,status,stable,infeasibility,penalty,iterations,seconds" }
local chart_points = {}
local total, converged_total = 0, 0
for _, sweep in ipairs(SWEEPS) do
  local counts, problems = {}, {}
  local grid = {}  -- grid[i][j]: result of value i, friction j
  for i, value in ipairs(sweep.values) do
    local s = sweep.build(value)
    grid[i] = {}
    for j, mu in ipairs(FRICTIONS) do
      local r = ashlar.analyze(s, { friction = mu })
      grid[i][j] = { status = r.status, infeasibility = r.infeasibility }
      counts[r.status] = (counts[r.status] or 0) + 1
      total = total + 1
      if r.status == "converged" then converged_total = converged_total + 1 end
      if r.infeasibility < 0 then
        problems[#problems + 1] = ("negative infeasibility %.3g at %g, mu = %g"):format(r.infeasibility, value, mu)
      end
      csv[#csv + 1] = ("%s,%.6g,%g,%s,%s,%.10g,%.10g,%d,%.4f"):format(sweep.name, value, mu, r.status,
        tostring(r.stable), r.infeasibility, r.penalty, r.iterations, r.seconds)
    end
  end
  for i = 1, #sweep.values do
    for j = 1, #FRICTIONS do
      local here = grid[i][j]
      if here.status == "numerical_error" then
        local neighbours = { grid[i - 1] and grid[i - 1][j], grid[i + 1] and grid[i + 1][j],
          grid[i][j - 1], grid[i][j + 1] }
        for _, n in pairs(neighbours) do
          if n.status == "converged" then
            problems[#problems + 1] = ("numerical_error at %g, mu = %g beside a converged neighbour"):format(
              sweep.values[i], FRICTIONS[j])
            break
          end
        end
      end
    end
  end
  local names = {}
  for status, n in pairs(counts) do names[#names + 1] = ("%s %d"):format(status, n) end
  table.sort(names)
  print(("%-5s %3d analyses: %s"):format(sweep.name, #sweep.values * #FRICTIONS, table.concat(names, ", ")))
  for _, line in ipairs(problems) do print("      " .. line) end
end
print(("all   %d analyses, %d converged (%.1f%%)"):format(total, converged_total, 100 * converged_total / total))

-- The chart's finer sweep.
local chart_arch = models.arch{ radius = 5, thickness = 0.3, voussoirs = 24 }
local unconverged = 0
for i = 0, 59 do
  local mu = 0.05 * (1e4 / 0.05) ^ (i / 59)
  local r = ashlar.analyze(chart_arch, { friction = mu })
  if r.status ~= "converged" then unconverged = unconverged + 1 end
  chart_points[#chart_points + 1] = { mu = mu, ["finite mu"] = r.infeasibility }
end
local no_sliding = ashlar.analyze(chart_arch, { friction = math.huge }).infeasibility
print(("chart: 60 frictions on the arch at t = 0.3 m, %d not converged; math.huge: %.6g"):format(unconverged,
  no_sliding))

support.write_atomically(folder .. "/solver_robustness.csv", table.concat(csv, "\n") .. "\n")
-- No sliding as a line across the chart, at both ends of the sweep.
local lowest, highest = chart_points[1].mu, chart_points[#chart_points].mu
chart_points[#chart_points + 1] = { mu = lowest, ["mu = math.huge"] = no_sliding }
chart_points[#chart_points + 1] = { mu = highest, ["mu = math.huge"] = no_sliding }
support.chart(folder .. "/solver_robustness_mu", { data = chart_points, x = "mu", y = { "finite mu", "mu = math.huge" },
  log_x = true, title = "Infeasibility against friction: arch R = 5 m, t = 0.3 m, 24 voussoirs",
  x_label = "friction coefficient mu", y_label = "infeasibility (tension / weight)" })
print("wrote " .. folder .. "/solver_robustness.csv and solver_robustness_mu.png/.svg")
