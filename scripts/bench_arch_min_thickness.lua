-- Benchmark: the minimum thickness of semicircular arches, found by bisection
-- on t/R with the equilibrium analysis (no sliding), against Milankovitch's
-- limit 0.1075 for infinitely many voussoirs.
--   ashlar scripts/bench_arch_min_thickness.lua [output folder, default "."]
-- Prints a table and writes arch_min_thickness.csv, .png and .svg (a log-log
-- chart of the error against the wall time of each bisection) in the folder.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"
local write_atomically = script_support.write_atomically

local LIMIT = 0.1075
local VOUSSOIRS = { 4, 8, 16, 32, 64, 128, 256, 512, 1024 }
local RADIUS = 5
-- Every count of voussoirs falls at the first ratio and stands at the second.
local BRACKET = { 0.05, 0.15 }
-- Far below the smallest error measured (about 2e-5), so that the error is
-- the model's and the analysis', not the bisection's.
local TOLERANCE = 1e-7

local output = arg[1] or "."
local base = output .. "/arch_min_thickness"

-- Bisection between a ratio at which the arch falls and one at which it
-- stands; returns the midpoint (nil if the bracket does not hold) and
-- figures about the analyses it ran.
local function minimum_thickness_ratio(voussoirs)
  local run = { voussoirs = voussoirs, analyses = 0, analysis_seconds = 0, iterations = 0, not_converged = 0 }
  local function stands(ratio)
    local s = models.arch{ radius = RADIUS, thickness = ratio * RADIUS, voussoirs = voussoirs }
    -- The general 6-equation solve, as in the committed figure; the planar
    -- one (the model's default) gives the same t/R about 1.5x faster.
    s:set_planar(false)
    local r = ashlar.analyze(s, { friction = math.huge })
    run.analyses = run.analyses + 1
    run.analysis_seconds = run.analysis_seconds + r.seconds
    run.iterations = run.iterations + r.iterations
    if r.status ~= "converged" then run.not_converged = run.not_converged + 1 end
    return r.stable
  end
  local start = ashlar.clock()
  local falling, standing = BRACKET[1], BRACKET[2]
  if not stands(falling) and stands(standing) then
    while standing - falling > TOLERANCE do
      local middle = (falling + standing) / 2
      if stands(middle) then standing = middle else falling = middle end
    end
    run.ratio = (falling + standing) / 2
    run.error = run.ratio - LIMIT
  end
  run.seconds = ashlar.clock() - start
  return run
end

-- The chart: error against bisection time, one marker per count of
-- voussoirs (named in the legend).
local function chart(runs)
  local rows = {}
  for _, run in ipairs(runs) do
    if run.ratio then rows[#rows + 1] = { seconds = run.seconds, error = math.abs(run.error), N = run.voussoirs } end
  end
  script_support.chart(base, { data = rows, x = "seconds", y = "error", series = "N", kind = "points",
    log_x = true, log_y = true,
    title = "Semicircular arch: minimum t/R by bisection (no sliding), error against Milankovitch's 0.1075",
    x_label = "wall time of the bisection (s)",
    y_label = "|t/R - 0.1075| (t: thickness, R: centreline radius)" })
end

script_support.make_folders(output)
local columns = "%9s %12s %14s %13s %9s %16s %15s %14s"
print(columns:format("voussoirs", "t/R found", "error", "bisection s", "analyses", "mean analysis s",
  "mean iterations", "not converged"))
local runs = {}
local csv = { "voussoirs,ratio,error_vs_0.1075,bisection_seconds,analyses,mean_analysis_seconds,"
              .. "mean_iterations,not_converged" }
for _, voussoirs in ipairs(VOUSSOIRS) do
  local run = minimum_thickness_ratio(voussoirs)
  runs[#runs + 1] = run
  local mean_seconds, mean_iterations = run.analysis_seconds / run.analyses, run.iterations / run.analyses
  local ratio_text = run.ratio and ("%.7f"):format(run.ratio) or "bracket fails"
  local error_text = run.error and ("%+.2e"):format(run.error) or ""
  print(columns:format(voussoirs, ratio_text, error_text, ("%.3f"):format(run.seconds), run.analyses,
    ("%.5f"):format(mean_seconds), ("%.1f"):format(mean_iterations), run.not_converged))
  csv[#csv + 1] = ("%d,%s,%s,%.6f,%d,%.6f,%.2f,%d"):format(voussoirs, run.ratio and ("%.9f"):format(run.ratio) or "",
    run.error and ("%.9e"):format(run.error) or "", run.seconds, run.analyses, mean_seconds, mean_iterations,
    run.not_converged)
end
write_atomically(base .. ".csv", table.concat(csv, "\n") .. "\n")
chart(runs)
print(("wrote %s.csv, %s.png, %s.svg"):format(base, base, base))
