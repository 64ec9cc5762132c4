-- Benchmark of the equilibrium analysis against block count, on running-bond
-- walls and semicircular barrel vaults, with cvxopt on the same QP as a
-- reference for speed and for the optimum.
--   ashlar scripts/bench_analysis.lua [output folder] [--charts]
-- Writes analysis_scaling.csv and log-log charts against blocks of time
-- (analysis_scaling.png/.svg) and peak memory (analysis_memory.png/.svg) to
-- the folder (default "."); with --charts, only draws the charts again from
-- the CSV already there. Each size runs in its own process so that its
-- peak memory is its own. cvxopt (Debian's python3-cvxopt, through
-- tests/tools/solve_qps.py) solves the exported QP for the smaller sizes;
-- only its solve is timed, not reading the file.
-- ashlar chooses its own threads (from 2,000 rows its factorisation is
-- split in two halves factored on two cores, each with one-threaded BLAS;
-- its per-group passes run on both cores; see
-- engine/core/sparse_cholesky.cpp); cvxopt runs with single-threaded
-- BLAS (OPENBLAS_NUM_THREADS=1), so its figures are per core.
-- "whole / factor" is the analysis time over the time of one factorisation
-- of its normal matrix (split or whole, as the analysis ran it): how close
-- to the cost floor of an interior point (one factorisation per iteration)
-- the method runs.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local FRICTION = 0.7
-- cvxopt runs up to this many blocks. Sizes grow about 3x a step and its
-- time about 10x (it re-analyses its sparse KKT pattern every iteration), so
-- once a solve takes CVXOPT_TIME_LIMIT seconds the next size is skipped.
local CVXOPT_MAX_BLOCKS = 3500
local CVXOPT_TIME_LIMIT = 30
local CVXOPT_TIMEOUT = 600  -- seconds; a solve this long counts as failed
local PYTHON = "/usr/bin/python3"  -- Debian's, which has python3-cvxopt

local script_folder = arg[0]:match("^(.*)/[^/]*$") or "."
local SOLVE_QPS = script_folder .. "/../tests/tools/solve_qps.py"

local function quote(text)
  return "'" .. text:gsub("'", [['\'']]) .. "'"
end

-- Running-bond walls of about 100 ... 20,000 bricks: bricks per course x courses.
local WALLS = { { 10, 10 }, { 20, 15 }, { 40, 25 }, { 60, 50 }, { 100, 100 }, { 200, 100 } }
-- Barrel vaults: voussoirs per course x courses.
local VAULTS = { { 20, 5 }, { 20, 15 }, { 25, 40 }, { 25, 120 }, { 50, 200 }, { 50, 400 } }

-- Walls are analysed with the general 6-equation solve, as vaults must be
-- (models.wall marks them planar, which is 2-3x faster at the same answer).
local function wall(per_course, courses)
  local brick = { 0.24, 0.07 }
  local s = models.wall{ length = per_course * brick[1], height = courses * brick[2], brick = brick }
  s:set_planar(false)
  return s
end

-- Thickness / radius = 0.2, about twice the minimum of a semicircular arch,
-- so the vault stands; courses of 0.25 m in running bond.
local function vault(voussoirs, courses)
  return models.barrel_vault{ radius = 2, thickness = 0.4, voussoirs = voussoirs, courses = courses,
                              length = 0.25 * courses, bond = "running" }
end

local BUILDERS = { wall = wall, vault = vault }
local SIZES = { wall = WALLS, vault = VAULTS }

local CSV_HEADER = "structure,blocks,interfaces,vertices,status,stable,iterations,factorizations," ..
  "objective,contacts_s,setup_s,assembly_s,factorization_s,solve_s,analysis_s,peak_mb," ..
  "cvxopt_status,cvxopt_iterations,cvxopt_objective,cvxopt_s"

-- Runs solve_qps.py on the structure's QP; returns status, iterations,
-- objective and solve seconds ("none" when cvxopt could not finish).
local function solve_with_cvxopt(s)
  local path = os.tmpname()
  ashlar.export_qp(s, path, { friction = FRICTION })
  local command = ("OPENBLAS_NUM_THREADS=1 timeout %d %s %s %s 2>&1"):format(CVXOPT_TIMEOUT, PYTHON, quote(SOLVE_QPS),
    quote(path))
  local pipe = assert(io.popen(command))
  local output = pipe:read("a")
  pipe:close()
  os.remove(path)
  local status = output:match('"status": "([^"]*)"')
  if not status then
    io.stderr:write("bench_analysis: cvxopt did not finish:\n", output)
    return "none", "", "", ""
  end
  local function field(name) return output:match('"' .. name .. '": ([^,}]+)') or "" end
  return status, field("iterations"), field("objective"), field("solve_seconds")
end

-- One size, in this process: a CSV line.
local function measure(kind, size_index, with_cvxopt)
  local size = SIZES[kind][size_index]
  local s = BUILDERS[kind](size[1], size[2])
  local t0 = ashlar.clock()
  local interfaces = s:interfaces()
  local contacts_seconds = ashlar.clock() - t0
  -- The contacts are cached now, so the analysis times the QP only.
  local r = ashlar.analyze(s, { friction = FRICTION })
  local peak = ashlar.memory().peak_mb
  local t = r.timings
  local fields = { kind, #s, #interfaces, #r.vertices, r.status, tostring(r.stable), r.iterations,
    r.factorizations, ("%.17g"):format(r.objective), contacts_seconds, t.setup, t.assembly,
    t.factorization, t.solve, r.seconds, ("%.1f"):format(peak) }
  local cvxopt = { "", "", "", "" }
  if with_cvxopt then cvxopt = { solve_with_cvxopt(s) } end
  for _, value in ipairs(cvxopt) do fields[#fields + 1] = value end
  for i, value in ipairs(fields) do
    if math.type(value) == "float" then fields[i] = ("%.6g"):format(value) end
  end
  return table.concat(fields, ",")
end

if arg[1] == "--measure" then
  print(measure(arg[2], tonumber(arg[3]), arg[4] == "cvxopt"))
  return
end

local support = require "script_support"
local write_atomically = support.write_atomically

local function split_csv(line)
  local fields = {}
  for field in (line .. ","):gmatch("([^,]*),") do fields[#fields + 1] = field end
  return fields
end

local CHARTS = {
  {
    name = "analysis_scaling",
    title = "Equilibrium analysis time against block count (friction 0.7, 4-sided pyramid)",
    ylabel = "wall-clock time (s)",
    series = {
      { kind = "wall", column = "analysis_s", title = "ashlar, running-bond wall" },
      { kind = "vault", column = "analysis_s", title = "ashlar, barrel vault" },
      { kind = "wall", column = "cvxopt_s", title = "cvxopt (solve only), running-bond wall" },
      { kind = "vault", column = "cvxopt_s", title = "cvxopt (solve only), barrel vault" },
    },
  },
  {
    name = "analysis_memory",
    title = "Peak memory of building and analysing a structure against block count",
    ylabel = "peak resident memory (MiB)",
    series = {
      { kind = "wall", column = "peak_mb", title = "ashlar, running-bond wall" },
      { kind = "vault", column = "peak_mb", title = "ashlar, barrel vault" },
    },
  },
}
local log_chart = dofile((arg[0]:match("^(.*)/") or ".") .. "/log_chart.lua")

local charts_only = support.charts_only()
local folder = arg[1] or "."
local csv_path = folder .. "/analysis_scaling.csv"

-- The charts from the rows (one per CSV line); returns the files written.
local function draw_charts(rows)
  local written = {}
  for _, chart in ipairs(CHARTS) do
    log_chart.draw_all(chart, rows, folder .. "/" .. chart.name)
    written[#written + 1] = ("%s/%s.png, .svg"):format(folder, chart.name)
  end
  return written
end

if charts_only then
  print("wrote " .. table.concat(draw_charts(support.read_csv(csv_path)), ", ") .. " from " .. csv_path)
  return
end

local interpreter = arg[-1] or "ashlar"
local header_names = split_csv(CSV_HEADER)
local csv_lines = { CSV_HEADER }
local rows = {}
local started = ashlar.clock()
-- Times are wall-clock: other work on the machine shows in them.
local load_file = io.open("/proc/loadavg")
if load_file then
  print("load average before the run: " .. load_file:read("l"):match("^(%S+ %S+ %S+)"))
  load_file:close()
end
print(("%-6s %7s %10s %9s %5s %5s %9s %9s %9s %9s %9s %8s %8s %9s %8s %10s"):format("", "blocks",
  "interfaces", "vertices", "iter", "fact", "setup s", "assemb s", "factor s", "solve s", "total s",
  "whole/f", "peak MiB", "cvxopt s", "speedup", "rel. diff"))
for _, kind in ipairs{ "wall", "vault" } do
  local cvxopt_stopped_at
  for size_index in ipairs(SIZES[kind]) do
    local size = SIZES[kind][size_index]
    local with_cvxopt = not cvxopt_stopped_at and size[1] * size[2] <= CVXOPT_MAX_BLOCKS
    local command = ("%s %s --measure %s %d %s"):format(quote(interpreter),
      quote(arg[0]), kind, size_index, with_cvxopt and "cvxopt" or "ashlar")
    local pipe = assert(io.popen(command))
    local line = pipe:read("l")
    pipe:close()
    assert(line and line:match("^" .. kind .. ","), "measurement failed: " .. command)
    csv_lines[#csv_lines + 1] = line
    local row = {}
    for i, value in ipairs(split_csv(line)) do row[header_names[i]] = value end
    rows[#rows + 1] = row
    local cvxopt_seconds, speedup, difference = tonumber(row.cvxopt_s), "", ""
    if cvxopt_seconds then
      speedup = ("%.1fx"):format(cvxopt_seconds / tonumber(row.analysis_s))
      local objective, reference = tonumber(row.objective), tonumber(row.cvxopt_objective)
      difference = row.cvxopt_status ~= "optimal" and "cvxopt: " .. row.cvxopt_status or
        ("%.1e"):format(math.abs(objective - reference) / math.max(math.abs(reference), 1e-300))
      if cvxopt_seconds > CVXOPT_TIME_LIMIT then cvxopt_stopped_at = tonumber(row.blocks) end
    elseif with_cvxopt then
      cvxopt_stopped_at = tonumber(row.blocks)
    end
    local one_factorization = tonumber(row.factorization_s) / math.max(tonumber(row.factorizations), 1)
    print(("%-6s %7d %10d %9d %5d %5d %9.3f %9.3f %9.3f %9.3f %9.3f %8.1f %8.1f %9s %8s %10s%s"):format(kind,
      row.blocks, row.interfaces, row.vertices, row.iterations, row.factorizations, row.setup_s,
      row.assembly_s, row.factorization_s, row.solve_s, row.analysis_s,
      tonumber(row.analysis_s) / one_factorization, row.peak_mb,
      cvxopt_seconds and ("%.3f"):format(cvxopt_seconds) or "-", speedup, difference,
      row.status == "converged" and "" or "  (" .. row.status .. ")"))
  end
  if cvxopt_stopped_at then
    print(("cvxopt: not run on %s structures above %d blocks: it took over %d s (or failed) there"):format(
      kind, cvxopt_stopped_at, CVXOPT_TIME_LIMIT))
  end
end
print(("cvxopt: not run above %d blocks. \"total s\" is ashlar's analysis without contact detection;"):format(
  CVXOPT_MAX_BLOCKS) .. " speedup = cvxopt's solve time / ashlar's total")

write_atomically(csv_path, table.concat(csv_lines, "\n") .. "\n")
local written = { csv_path }
for _, path in ipairs(draw_charts(rows)) do written[#written + 1] = path end
print(("wrote %s in %.0f s"):format(table.concat(written, ", "), ashlar.clock() - started))
