-- A recorded-format ground motion on a masonry wall, as an engineer runs it:
-- a synthetic accelerogram written as a PEER NGA AT2 file, read back with
-- ashlar.ground_motion, and a running-bond wall shaken by it along its
-- length; prints the run's cost and the engineer's summary, and draws the
-- displacements against time.
--   ashlar scripts/record_wall.lua [PGA in g (default 0.3)] [duration s (default 20)]
--                                  [bricks per course (default 100)] [output folder (default .)]
-- The defaults are the 1,006-block wall of scripts/bench_simulate.lua for
-- 20 s (about a quarter of an hour of a core); `0.3 0.5 10` is a quick check
-- on 106 blocks.
--
-- The record: Gaussian white noise (Lua's seeded generator, seed 55,
-- Box-Muller), held over each sample, through a Kanai-Tajimi ground filter
-- (Tajimi 1960) for firm ground, omega_g = 15.6 rad/s (2.5 Hz), zeta_g =
-- 0.6: the filter's mass obeys x'' + 2 zeta_g omega_g x' + omega_g^2 x =
-- -w(t) (RK4, 10 sub-steps a sample), and the ground's acceleration is
-- its absolute one, -(2 zeta_g omega_g x' + omega_g^2 x). A Jennings-type
-- envelope (Jennings, Housner & Tsai 1968) shapes it over the duration D:
-- (t / t1)^2 rising to t1 = 0.1 D, 1 in the strong phase to t2 = 0.5 D,
-- exp(-8 (t - t2) / D) decaying after (2 % of the peak at the end). The
-- samples are then scaled so that their peak is the PGA. DT = 0.01 s.
--
-- The file: the AT2 layout PEER's database uses (four header lines, the
-- units "G", five values a line in E format with 7 decimals); read back,
-- every sample must equal the generated one to 1e-6 of itself (the
-- format's 8 significant digits), or the script stops with an error.
--
-- The wall: models.wall{ length = bricks x 0.24, height = 10 x 0.07,
-- brick = {0.24, 0.07} } (bricks x 10 + 6 blocks with the ground), friction
-- 0.6, steps of 1 ms, the record along x (the wall's length), frames every
-- 20 steps (0.02 s). Times: the run's wall-clock time (sim.seconds) and
-- the process's CPU time over it (os.clock), which a shared machine
-- inflates less. Timing never fails anything: this prints figures.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local pga = tonumber(arg[1] or "0.3")
local duration = tonumber(arg[2] or "20")
local per_course = math.tointeger(tonumber(arg[3] or "100"))
local folder = arg[4] or "."
assert(pga and pga > 0, "PGA (argument 1) must be a number > 0 (g), got " .. tostring(arg[1]))
assert(duration and duration >= 0.1, "duration (argument 2) must be a number >= 0.1 (s), got " .. tostring(arg[2]))
assert(per_course and per_course >= 2, "bricks per course (argument 3) must be a whole number >= 2, got " ..
  tostring(arg[3]))
support.make_folders(folder)

local dt, omega_g, zeta_g, seed = 0.01, 15.6, 0.6, 55

-- The generated samples (g), k = 0 .. n - 1 at k dt, before scaling.
local function kanai_tajimi(count)
  math.randomseed(seed)
  local function gaussian()
    return math.sqrt(-2 * math.log(1 - math.random())) * math.cos(2 * math.pi * math.random())
  end
  local function rate(x, v, w) return v, -w - 2 * zeta_g * omega_g * v - omega_g * omega_g * x end
  local t1, t2 = 0.1 * duration, 0.5 * duration
  local function envelope(t)
    if t < t1 then return (t / t1) ^ 2 end
    if t <= t2 then return 1 end
    return math.exp(-8 * (t - t2) / duration)
  end
  local samples, x, v, substeps = {}, 0, 0, 10
  local h = dt / substeps
  for k = 0, count - 1 do
    samples[k + 1] = -(2 * zeta_g * omega_g * v + omega_g * omega_g * x) * envelope(k * dt)
    local w = gaussian()
    for _ = 1, substeps do
      local k1x, k1v = rate(x, v, w)
      local k2x, k2v = rate(x + 0.5 * h * k1x, v + 0.5 * h * k1v, w)
      local k3x, k3v = rate(x + 0.5 * h * k2x, v + 0.5 * h * k2v, w)
      local k4x, k4v = rate(x + h * k3x, v + h * k3v, w)
      x, v = x + h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x), v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)
    end
  end
  local peak = 0
  for _, a in ipairs(samples) do peak = math.max(peak, math.abs(a)) end
  for k, a in ipairs(samples) do samples[k] = a * pga / peak + 0.0 end  -- no -0 in the file
  return samples
end

local count = math.floor(duration / dt + 0.5) + 1
local samples = kanai_tajimi(count)
local path = folder .. "/record_wall.at2"
local lines = {
  "PEER NGA STRONG MOTION DATABASE RECORD",
  ("ASHLAR SYNTHETIC RECORD: KANAI-TAJIMI (OMEGA_G 15.6 RAD/S, ZETA_G 0.6), JENNINGS ENVELOPE, SEED %d, PGA %.3g G")
    :format(seed, pga),
  "ACCELERATION TIME SERIES IN UNITS OF G",
  ("NPTS=%7d, DT=%9.4f SEC"):format(count, dt),
}
for first = 1, count, 5 do
  local row = {}
  for k = first, math.min(first + 4, count) do row[#row + 1] = ("%15.7E"):format(samples[k]) end
  lines[#lines + 1] = table.concat(row)
end
support.write_atomically(path, table.concat(lines, "\n") .. "\n")

local record = ashlar.ground_motion{ path = path, component = "x" }
local worst = 0
for k = 1, count do
  local a = record((k - 1) * dt) / 9.81  -- ashlar's g (m/s^2)
  local error = math.abs(a - samples[k])
  assert(error <= 1e-6 * math.abs(samples[k]), ("%s: sample %d read back as %.9g g, generated %.9g g"):format(path,
    k - 1, a, samples[k]))
  if samples[k] ~= 0 then worst = math.max(worst, error / math.abs(samples[k])) end
end
assert(math.abs(record.peak / 9.81 - pga) <= 1e-6 * pga, ("%s: peak %.9g g read back, %.9g g generated"):format(
  path, record.peak / 9.81, pga))
print(("record: %s, %d samples at %.2f s (%.2f s), peak %.4f g at %.2f s; read back to %.2g of each sample")
  :format(path, count, dt, record.duration, record.peak / 9.81, record.peak_time, worst))

local brick = { 0.24, 0.07 }
local wall = models.wall{ length = per_course * brick[1], height = 10 * brick[2], brick = brick }
local cpu = os.clock()
local sim = ashlar.simulate(wall, { duration = duration, step = 1e-3, friction = 0.6, record_every = 20,
  ground_acceleration = record })
cpu = os.clock() - cpu

-- The top course: the free blocks whose centroids are highest.
local top, height = {}, -math.huge
for i = 1, #wall do
  if not wall:is_support(i) then height = math.max(height, wall:block(i):centroid()[3]) end
end
for i = 1, #wall do
  if not wall:is_support(i) and wall:block(i):centroid()[3] > height - 1e-9 then top[#top + 1] = i end
end

local summary, drift = sim:summary(), sim:drift(top)
print(("wall: %d blocks, %d bricks a course, 10 courses, friction 0.6, steps of 1 ms"):format(#wall, per_course))
print(("run: %s, %d steps, %.1f s wall-clock (%.2f s per simulated s), %.1f s CPU (%.2f s per simulated s), " ..
  "%d unconverged steps, %.1f sweeps a step"):format(sim.status, sim.steps, sim.seconds, sim.seconds / sim.time, cpu,
  cpu / sim.time, sim.unconverged_steps, sim.sweeps / sim.steps))
print(("summary: peak displacement %.4g m (block %s), residual %.4g m (block %s)"):format(summary.peak_displacement,
  tostring(summary.peak_block), summary.residual_displacement, tostring(summary.residual_block)))
local function when(t) return t and ("%.2f s"):format(t) or "none" end
print(("summary: first movement %s, collapsed %s, collapse time %s, %d blocks fell"):format(
  when(summary.first_movement), tostring(summary.collapsed), when(summary.collapse_time), #summary.fallen))
print(("drift of the top course (%d blocks, %.3f m above the base): peak %.4g, residual %.4g"):format(#top,
  drift.height, drift.peak, drift.residual))
local chart = sim:chart{ path = folder .. "/record_wall_displacement.png",
  title = ("Wall of %d blocks under a %g s synthetic record, PGA %.2f g"):format(#wall, duration, pga) }
print("chart: " .. chart.path)
