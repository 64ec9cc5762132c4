-- A study across MPI ranks gives the table a local run gives. Run by ctest
-- as `ashlar study_mpi.lua <mpiexec> <thicknesses>` when the build has MPI
-- (tests/CMakeLists.txt says how many thicknesses, and why).
local support = require "spec_support"
local quote = support.quote

local mpiexec = assert(arg[1], "usage: ashlar study_mpi.lua <mpiexec> <thicknesses>")
local THICKNESSES = assert(math.tointeger(tonumber(arg[2])), "usage: ashlar study_mpi.lua <mpiexec> <thicknesses>")
local ashlar_bin = assert(arg[-1], "run by the ashlar host")
local folder = support.temp_folder()

-- The example sweep with THICKNESSES thicknesses (× 3 voussoir counts × 2
-- frictions: enough analyses for every rank to run rows): arguments db,
-- workers, csv, thicknesses.
local sweep = quote(support.script_folder(1) .. "/../../scripts/arch_sweep.lua")
local ROWS = THICKNESSES * 3 * 2

local function run(command)
  local output, code = support.run("cd " .. quote(folder) .. " && " .. command)
  assert(code == 0, command .. " failed:\n" .. output)
  return output
end

run(quote(ashlar_bin) .. " " .. sweep .. " local.sqlite 1 local.csv " .. THICKNESSES)
local output = run(quote(mpiexec) .. " --oversubscribe -np 3 " .. quote(ashlar_bin) .. " " .. sweep .. " mpi.sqlite 1 mpi.csv " .. THICKNESSES)
-- Rank 0 alone reports, and ran every row (in its thread or on the other ranks).
assert(output:find("runs " .. ROWS .. " seconds [%d.]+ runs_per_second [%d.]+ workers 3 errors 0"), output)

local function lines(path)
  local list = {}
  for line in support.read_file(folder .. "/" .. path):gmatch("[^\r\n]+") do list[#list + 1] = line end
  return list
end
local expected, got = lines("local.csv"), lines("mpi.csv")
-- a header and a line per row
assert(#expected == ROWS + 1 and #got == ROWS + 1, "expected " .. ROWS + 1 .. " lines, got " .. #expected .. " and " .. #got)
local workers = {}
for i = 1, #expected do
  -- every column but run_seconds and run_worker
  local a, b = expected[i]:match("^(.*),[^,]*,[^,]*$"), got[i]:match("^(.*),[^,]*,[^,]*$")
  assert(a == b, ("line %d differs:\n  local %s\n  MPI   %s"):format(i, a, b))
  workers[got[i]:match(",([^,]*)$")] = true
end
-- Rank 0's worker thread is worker 1; ranks 1 and 2 are 1001 and 2001.
assert(workers["1001"] and workers["2001"], "ranks 1 and 2 ran no rows")

-- run = "module.function" (fixtures/study_run): every rank runs the script
-- once, as its main program, and requires the module in its state; rank 0's
-- worker thread requires it too and does not run the script again.
local ashlar = require "ashlar"
local box_study = quote(support.script_folder(1) .. "/fixtures/study_run/box_study.lua")
-- The ranks, all on this machine, inherit mpiexec's environment (no -x:
-- the sanitizer suite passes its options through mca_base_env_list, which
-- Open MPI does not let -x join).
run("ASHLAR_STUDY_LOG=boxes.log ASHLAR_STUDY_ROW_SECONDS=0.02 " .. quote(mpiexec) ..
    " --oversubscribe -np 3 " .. quote(ashlar_bin) .. " " .. box_study .. " boxes.sqlite 1 module")
local log = support.read_file(folder .. "/boxes.log")
local _, scripts = log:gsub("script\n", "")
local _, modules = log:gsub("module\n", "")
assert(scripts == 3, "the script ran " .. scripts .. " times on 3 ranks, expected once per rank")
assert(modules == 4, "the module was loaded " .. modules .. " times, expected once per rank and once in rank 0's thread")
local box_workers = {}
local boxes = ashlar.load_study{ db = folder .. "/boxes.sqlite", name = "boxes" }:rows()
assert(#boxes == 24, "expected 24 box rows, got " .. #boxes)
for _, row in ipairs(boxes) do
  assert(row.run_status == "ok", row.run_error)
  local volume = row.a * row.b * row.c
  assert(math.abs(row.mass - 2400 * volume) <= 1e-12 * 2400 * volume, "mass " .. row.mass .. " of a box of " .. volume .. " m3")
  assert(row.rank == row.run_worker // 1000, "row of worker " .. row.run_worker .. " ran on rank " .. row.rank)
  box_workers[row.run_worker] = true
end
assert(box_workers[1001] or box_workers[2001], "ranks 1 and 2 ran no box rows")
support.remove_folder(folder)
print("MPI study with 3 ranks: " .. ROWS .. " rows, identical to the local run; the module form ran the script once per rank")
