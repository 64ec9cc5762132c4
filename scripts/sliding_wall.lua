-- A running-bond wall of 0.4 x 0.2 x 0.2 m bricks on the ground (friction
-- 0.6) shaken along its length at A sin(2 pi f t), simulated, beside the
-- rigid block sliding on its base in closed form (scripts/sliding_block.lua):
--   ashlar scripts/sliding_wall.lua BRICKS_A_COURSE COURSES A_IN_G F_HZ DURATION_S [MAX_SWEEPS]
-- e.g. 5 5 1.5 2 0.3. Where the wall's load factor along its length
-- (ashlar.load_factor at the same friction) is the friction itself, its
-- base's sliding is its first mechanism: past it the wall slides whole as
-- the closed form's block, every bed joint above the base at its friction
-- limit without slipping. Below it (10 10, the 106-block wall of
-- scripts/bench_simulate.lua: 0.52) the wall has a mechanism of its own
-- and the closed form does not apply. Prints the load factor, the run's
-- steps, unconverged steps, sweeps a step and seconds, the closed form's
-- displacement at the end and every brick's range.
local ashlar = require "ashlar"
local models = require "ashlar.models"
package.path = "scripts/?.lua;" .. package.path
local sliding = require "sliding_block"

local per_course, courses = tonumber(arg[1]), tonumber(arg[2])
local amplitude, frequency, duration = tonumber(arg[3]), tonumber(arg[4]), tonumber(arg[5])
local max_sweeps = tonumber(arg[6])  -- nil: simulate's default
if not (per_course and courses and amplitude and frequency and duration) then
  io.stderr:write("usage: ashlar scripts/sliding_wall.lua BRICKS_A_COURSE COURSES A_IN_G F_HZ DURATION_S [MAX_SWEEPS]\n")
  os.exit(1)
end
local mu, a, w = 0.6, amplitude * 9.81, 2 * math.pi * frequency
local s = models.wall{ length = per_course * 0.4, height = courses * 0.2, thickness = 0.2, brick = { 0.4, 0.2 } }
s:set_planar(false)
local factor = ashlar.load_factor(s, { friction = mu, direction = { -1, 0, 0 } }).factor
local sim = ashlar.simulate(s, { duration = duration, friction = mu, max_sweeps = max_sweeps,
  ground_acceleration = function(t) return a * math.sin(w * t), 0, 0 end })
local lo, hi = math.huge, -math.huge
for i = 1, #s do
  if not s:is_support(i) then
    local positions = sim:trajectory(i).positions
    local x = positions[#positions][1] - positions[1][1]
    lo, hi = math.min(lo, x), math.max(hi, x)
  end
end
print(("%d blocks, load factor %.4g; %g g, %g Hz, %g s: %d steps, %d unconverged (largest residual %.2g m/s), "
  .. "%d split, %.1f sweeps a step, %.2f s"):format(#s, factor, amplitude, frequency, duration, sim.steps,
  sim.unconverged_steps, sim.max_residual, sim.split_steps, sim.sweeps / sim.steps, sim.seconds))
print(("closed form %.7f m; the blocks %.7f to %.7f m"):format(sliding.displacement(a, w, mu, sim.time), lo, hi))
