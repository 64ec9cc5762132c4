-- Benchmark of ashlar.simulate: time per simulated second against block
-- count, and peak memory.
--   ashlar scripts/bench_simulate.lua [folder for bench_simulate.csv and charts (default .)] [duration s (default 0.1)] [all]
-- Structures: running-bond walls 10 courses high, 10, 100 and 1,000 bricks
-- long (100, 1,000 and 10,000 blocks), standing from rest (`at rest`), and
-- the same walls with their ground shaken along their length at 0.3 g,
-- 2 Hz (`shaken`; the 10,000-block one only with `all`: about 5 minutes
-- per 0.1 s simulated). Each run is its own process, so that peak memory is its
-- own. The first step costs most (the contact impulses start at zero, no
-- prestress); later steps start from the last step's impulses, so both are
-- reported. Timing never fails anything: this prints figures.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local brick = { 0.24, 0.07 }

local function wall(per_course)
  return models.wall{ length = per_course * brick[1], height = 10 * brick[2], brick = brick }
end

local function shaking(t) return 0.3 * 9.81 * math.sin(2 * math.pi * 2 * t), 0, 0 end

-- One measurement: blocks, contact points, steps, seconds, ...
local function measure(kind, per_course, duration)
  local s = wall(per_course)
  s:interfaces()  -- detection is not the simulation's cost
  local first = ashlar.simulate(s, { duration = 1e-3, friction = 0.6,
                                     ground_acceleration = kind == "shaken" and shaking or nil })
  local sim = ashlar.simulate(s, { duration = duration, friction = 0.6,
                                   ground_acceleration = kind == "shaken" and shaking or nil })
  return ("%s,%d,%d,%d,%.6f,%.6f,%.6f,%.1f,%d,%d,%.3g,%.1f"):format(kind, #s, sim.max_active_contacts, sim.steps,
    first.seconds, sim.seconds, sim.seconds / sim.time, sim.sweeps / sim.steps, sim.unconverged_steps, sim.searches,
    sim.max_displacement, ashlar.memory().peak_mb)
end

if arg[1] == "--measure" then
  print(measure(arg[2], tonumber(arg[3]), tonumber(arg[4])))
  return
end

local folder = arg[1] or "."
local duration = tonumber(arg[2] or "0.1")
local all = arg[3] == "all"
local interpreter, script = arg[-1] or "ashlar", arg[0]
local header = "structure,blocks,contacts,steps,first_step_s,run_s,s_per_simulated_s,sweeps_per_step," ..
  "unconverged_steps,searches,max_displacement_m,peak_mb"
local rows, lines = {}, { header }
print(("%-8s %7s %9s %6s %12s %10s %14s %12s %12s %9s %10s"):format("wall", "blocks", "contacts", "steps",
  "1st step s", "run s", "s / sim. s", "sweeps/step", "unconverged", "searches", "peak MiB"))
for _, kind in ipairs{ "at rest", "shaken" } do
  for _, per_course in ipairs(kind == "shaken" and not all and { 10, 100 } or { 10, 100, 1000 }) do
    local command = ("%q %q --measure %q %d %g"):format(interpreter, script, kind, per_course, duration)
    local pipe = assert(io.popen(command))
    local line = pipe:read("l")
    pipe:close()
    assert(line and line:match("^[%a ]+,%d"), "measurement failed for " .. command)
    lines[#lines + 1] = line
    local f = {}
    for field in line:gmatch("[^,]+") do f[#f + 1] = field end
    rows[#rows + 1] = { structure = f[1], blocks = tonumber(f[2]), per_second = tonumber(f[7]),
                        first = tonumber(f[5]) }
    print(("%-8s %7d %9d %6d %12.3f %10.3f %14.2f %12.1f %12d %9d %10.1f"):format(f[1], f[2], f[3], f[4], f[5],
      f[6], f[7], f[8], f[9], f[10], f[12]))
  end
end
local csv_path = folder .. "/bench_simulate.csv"
support.write_atomically(csv_path, table.concat(lines, "\n") .. "\n")
print("wrote " .. csv_path)
local log_chart = dofile((script:match("^(.*)/[^/]*$") or ".") .. "/log_chart.lua")
log_chart.draw_all({ title = "ashlar.simulate: running-bond walls, 10 courses, step 1 ms",
                     ylabel = "wall-clock seconds per simulated second",
                     series = { { kind = "at rest", column = "per_second", title = "at rest" },
                                { kind = "shaken", column = "per_second", title = "ground 0.3 g, 2 Hz" } } },
  rows, folder .. "/bench_simulate")
