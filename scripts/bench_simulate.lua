-- Benchmark of ashlar.simulate: time per simulated second against block
-- count, solver work and peak memory, with Bullet's time and answer on the
-- same walls beside ours, and a collapsing arch.
--   ashlar scripts/bench_simulate.lua [folder for bench_simulate.csv and charts (default .)] [duration s (default 0.1)] [all]
-- Structures: running-bond walls 10 courses high, 10, 100 and 1,000 bricks
-- long (106, 1,006 and 10,006 blocks with the ground), standing from rest
-- (`at rest`), and the same walls with their ground shaken along their
-- length at 0.3 g, 2 Hz (`shaken`; the 10,006-block one only with `all`),
-- friction 0.6, steps of 1 ms. Nothing should move: 0.3 g is below the
-- friction limit and the blocks' uplift threshold, so the largest
-- displacement measures each engine's error. Then a semicircular arch of
-- 22 voussoirs below its minimum thickness (radius 5, thickness 0.45)
-- collapsing for 1.5 s. Each run is its own process, so that peak memory
-- is its own. The first step costs most (the contact impulses start at
-- zero, no prestress); later steps start from the last step's impulses, so
-- both are reported. Times: the run's wall-clock time (sim.seconds), and
-- the process's CPU time (os.clock: all its threads), which a shared
-- machine inflates less.
-- Bullet: bench/bullet_walls.cpp (Debian's libbullet-dev, double
-- precision, sequential impulses, 10 iterations, no sleeping) on the same
-- blocks, the shake as -m a_g(t) on every block; built as the CMake target
-- bench_bullet_walls when the build folder (beside the ashlar binary's
-- bin/) has it configured; left out when it cannot be built. Its time is
-- the CPU time of its stepping.
-- Timing never fails anything: this prints figures.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local brick = { 0.24, 0.07 }
local amplitude, frequency = 0.3 * 9.81, 2

local function wall(per_course)
  return models.wall{ length = per_course * brick[1], height = 10 * brick[2], brick = brick }
end

local function shaking(t) return amplitude * math.sin(2 * math.pi * frequency * t), 0, 0 end

local function arch() return models.arch{ radius = 5, thickness = 0.45, voussoirs = 22 } end

-- One measurement: blocks, contact points, steps, seconds, ...
local function measure(kind, per_course, duration)
  local s, options
  if kind == "arch" then
    s, options = arch(), { friction = 0.7 }
  else
    s, options = wall(per_course), { friction = 0.6, ground_acceleration = kind == "shaken" and shaking or nil }
  end
  s:interfaces()  -- detection is not the simulation's cost
  options.duration = 1e-3
  local first = ashlar.simulate(s, options)
  options.duration = duration
  local cpu = os.clock()
  local sim = ashlar.simulate(s, options)
  cpu = os.clock() - cpu
  return ("%s,%d,%d,%d,%.6f,%.6f,%.6f,%.6f,%.1f,%.2f,%d,%d,%.3g,%d,%.3g,%.1f"):format(kind, #s,
    sim.max_active_contacts, sim.steps, first.seconds, sim.seconds, sim.seconds / sim.time, cpu / sim.time,
    sim.sweeps / sim.steps,
    sim.global_steps / sim.steps, sim.factorizations, sim.unconverged_steps, sim.max_residual, sim.searches,
    sim.max_displacement, ashlar.memory().peak_mb)
end

-- The wall's blocks for bench_bullet_walls: "support cx cy cz sx sy sz density"
-- (every block of models.wall is an axis-aligned box).
local function write_boxes(per_course, path)
  local s, lines = wall(per_course), {}
  for i = 1, #s do
    local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
    for _, p in ipairs(s:block(i):vertices()) do
      for k = 1, 3 do lo[k], hi[k] = math.min(lo[k], p[k]), math.max(hi[k], p[k]) end
    end
    lines[#lines + 1] = ("%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g"):format(s:is_support(i) and 1 or 0,
      (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2, (lo[3] + hi[3]) / 2, hi[1] - lo[1], hi[2] - lo[2], hi[3] - lo[3],
      s:block(i):density())
  end
  support.write_atomically(path, table.concat(lines, "\n") .. "\n")
end

if arg[1] == "--measure" then
  print(measure(arg[2], tonumber(arg[3]), tonumber(arg[4])))
  return
end
if arg[1] == "--boxes" then
  write_boxes(tonumber(arg[2]), arg[3])
  return
end

local folder = arg[1] or "."
local duration = tonumber(arg[2] or "0.1")
local all = arg[3] == "all"
local interpreter, script = arg[-1] or "ashlar", arg[0]

-- Bullet's bench beside the interpreter (build/bin), built if its build
-- folder can; nil when there is none.
local function bullet_bench()
  local bin = interpreter:match("^(.*)/[^/]*$")
  if not bin then return nil end
  local bench = bin .. "/bench_bullet_walls"
  local build = bin:match("^(.*)/bin$")
  if build then
    os.execute(("cmake --build %s --target bench_bullet_walls >/dev/null 2>&1"):format(support.shell_quoted(build)))
  end
  local file = io.open(bench, "r")
  if not file then return nil end
  file:close()
  return bench
end
local bullet = bullet_bench()
print(bullet and ("Bullet: " .. bullet) or "Bullet: bench_bullet_walls not built (no libbullet-dev?): left out")

local function run(command)
  local pipe = assert(io.popen(command))
  local line = pipe:read("l")
  pipe:close()
  return line
end

local header = "structure,blocks,contacts,steps,first_step_s,run_s,s_per_simulated_s,cpu_s_per_simulated_s," ..
  "sweeps_per_step," ..
  "global_steps_per_step,factorizations,unconverged_steps,max_residual_m_s,searches,max_displacement_m,peak_mb," ..
  "bullet_cpu_s_per_simulated_s,bullet_max_displacement_m"
local rows, lines = {}, { header }
print(("%-8s %6s %8s %5s %9s %8s %9s %9s %7s %6s %6s %6s %9s %9s %7s %10s %9s"):format("run", "blocks",
  "contacts", "steps", "1st step", "run s", "s/sim. s", "CPU s/s", "sweeps", "global", "factor", "unconv",
  "residual", "max disp", "MiB", "Bullet s/s", "Bullet d"))
local cases = {}
for _, kind in ipairs{ "at rest", "shaken" } do
  for _, per_course in ipairs(kind == "shaken" and not all and { 10, 100 } or { 10, 100, 1000 }) do
    cases[#cases + 1] = { kind = kind, per_course = per_course, duration = duration }
  end
end
cases[#cases + 1] = { kind = "arch", per_course = 0, duration = 1.5 }
for _, case in ipairs(cases) do
  local command = ("%s %s --measure %s %d %g"):format(support.shell_quoted(interpreter), support.shell_quoted(script),
    support.shell_quoted(case.kind), case.per_course, case.duration)
  local line = run(command)
  assert(line and line:match("^[%a ]+,%d"), "measurement failed for " .. command)
  local bullet_line
  if bullet and case.kind ~= "arch" then
    local boxes = os.tmpname()
    run(("%s %s --boxes %d %s"):format(support.shell_quoted(interpreter), support.shell_quoted(script),
      case.per_course, boxes))
    bullet_line = run(("%s %s %g 0.6 %g %g"):format(support.shell_quoted(bullet), boxes, case.duration,
      case.kind == "shaken" and amplitude or 0, frequency))
    os.remove(boxes)
  end
  local b = {}
  for field in (bullet_line or ""):gmatch("[^,]+") do b[#b + 1] = field end
  line = line .. "," .. (b[5] or "") .. "," .. (b[6] or "")
  lines[#lines + 1] = line
  local f = {}
  for field in (line .. ","):gmatch("([^,]*),") do f[#f + 1] = field end
  rows[#rows + 1] = { structure = f[1], blocks = tonumber(f[2]), cpu_per_second = tonumber(f[8]),
                      bullet = tonumber(f[17]) }
  print(("%-8s %6d %8d %5d %9.3f %8.2f %9.2f %9.2f %7.1f %6.2f %6d %6d %9.2g %9.2g %7.1f %10s %9s"):format(f[1],
    f[2], f[3], f[4], f[5], f[6], f[7], f[8], f[9], f[10], f[11], f[12], f[13], f[15], f[16], f[17], f[18]))
end
local csv_path = folder .. "/bench_simulate.csv"
support.write_atomically(csv_path, table.concat(lines, "\n") .. "\n")
print("wrote " .. csv_path)
local log_chart = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/log_chart.lua")
log_chart.draw_all({ title = "ashlar.simulate and Bullet: running-bond walls, 10 courses, step 1 ms",
                     ylabel = "CPU seconds per simulated second",
                     series = { { kind = "at rest", column = "cpu_per_second", title = "ashlar, at rest" },
                                { kind = "shaken", column = "cpu_per_second", title = "ashlar, ground 0.3 g, 2 Hz" },
                                { kind = "at rest", column = "bullet", title = "Bullet, at rest" },
                                { kind = "shaken", column = "bullet", title = "Bullet, ground 0.3 g, 2 Hz" } } },
  rows, folder .. "/bench_simulate")
