-- Benchmark of contact detection on running-bond walls.
--   ashlar scripts/bench_interfaces.lua [csv path]
-- Each size runs in its own process so that peak memory is its own. Prints a
-- table and writes a CSV (default bench_interfaces.csv).
local ashlar = require "ashlar"
local models = require "ashlar.models"

local brick = { 0.24, 0.07 }

-- One measurement: bricks per course x courses.
local function measure(per_course, courses)
  local before = ashlar.memory()
  local t0 = ashlar.clock()
  local s = models.wall{ length = per_course * brick[1], height = courses * brick[2], brick = brick }
  local built = ashlar.memory()
  local t1 = ashlar.clock()
  local interfaces = s:interfaces()
  local t2 = ashlar.clock()
  local cached = s:interfaces()
  local t3 = ashlar.clock()
  local after = ashlar.memory()
  return string.format("%d,%d,%.6f,%.6f,%.6f,%.1f,%.1f,%.1f", #s, #interfaces, t1 - t0, t2 - t1,
    t3 - t2, before.resident_mb, built.peak_mb, after.peak_mb)
end

if arg[1] == "--measure" then
  print(measure(tonumber(arg[2]), tonumber(arg[3])))
  return
end

local csv_path = arg[1] or "bench_interfaces.csv"
local interpreter, script = arg[-1] or "ashlar", arg[0]
-- Walls whose block counts are about 1,000, 3,000, 10,000 and 30,000.
local sizes = { { 20, 10 }, { 50, 20 }, { 100, 20 }, { 100, 100 }, { 200, 150 } }
local header = "blocks,interfaces,build_s,interfaces_s,cached_s,baseline_mb,peak_after_build_mb,peak_mb"
local rows = { header }
print(("%8s %10s %10s %14s %12s %12s %14s"):format("blocks", "interfaces", "build s", "interfaces s",
  "cached s", "peak MiB", "contacts MiB"))
for _, size in ipairs(sizes) do
  local command = ("%q %q --measure %d %d"):format(interpreter, script, size[1], size[2])
  local pipe = assert(io.popen(command))
  local line = pipe:read("l")
  pipe:close()
  assert(line and line:match("^%d"), "measurement failed for " .. command)
  rows[#rows + 1] = line
  local blocks, count, build, detect, cached, _, built_peak, peak = line:match(
    "^(%d+),(%d+),([^,]+),([^,]+),([^,]+),([^,]+),([^,]+),([^,]+)$")
  print(("%8d %10d %10.3f %14.4f %12.6f %12.1f %14.1f"):format(blocks, count, build, detect, cached,
    peak, peak - built_peak))
end
local file = assert(io.open(csv_path .. ".tmp", "w"))
file:write(table.concat(rows, "\n"), "\n")
file:close()
assert(os.rename(csv_path .. ".tmp", csv_path))
print("wrote " .. csv_path)
