-- A study across MPI ranks gives the table a local run gives. Run by ctest
-- as `ashlar study_mpi.lua <mpiexec>` when the build has MPI.
local support = require "spec_support"
local quote = support.quote

local mpiexec = assert(arg[1], "usage: ashlar study_mpi.lua <mpiexec>")
local ashlar_bin = assert(arg[-1], "run by the ashlar host")
local folder = support.temp_folder()

support.write_file(folder .. "/sweep.lua", [[
local ashlar = require "ashlar"
local models = require "ashlar.models"
local study = ashlar.study{
  name = "arch", db = arg[1], workers = 1,
  params = { t = ashlar.range(0.09, 0.14, 11), n = { 8, 16 }, mu = { 0.5, 0.7 } },
  run = function(p)
    local r = ashlar.analyze(models.arch{ radius = 1, thickness = p.t, voussoirs = p.n }, { friction = p.mu })
    return { stable = r.stable, infeasibility = r.infeasibility }
  end,
}
study:csv(arg[2])
local rank, size = ashlar.rank()
-- Every rank ends with the whole table.
assert(#study == 44 and study:info().ok == 44, "rank " .. rank .. " has an incomplete table")
print(("rank %d of %d has %d rows"):format(rank, size, #study))
]])

local function run(command)
  local pipe = assert(io.popen("cd " .. quote(folder) .. " && { " .. command .. "\n} 2>&1"))
  local output = pipe:read("a")
  local _, _, code = pipe:close()
  assert(code == 0, command .. " failed:\n" .. output)
  return output
end

run(quote(ashlar_bin) .. " sweep.lua local.sqlite local.csv")
local output = run(quote(mpiexec) .. " --oversubscribe -np 3 " .. quote(ashlar_bin) .. " sweep.lua mpi.sqlite mpi.csv")
for rank = 0, 2 do
  assert(output:find(("rank %d of 3 has 44 rows"):format(rank), 1, true), output)
end

local function lines(path)
  local list = {}
  for line in support.read_file(folder .. "/" .. path):gmatch("[^\r\n]+") do list[#list + 1] = line end
  return list
end
local expected, got = lines("local.csv"), lines("mpi.csv")
assert(#expected == 45 and #got == 45, "expected 45 lines, got " .. #expected .. " and " .. #got)
local workers = {}
for i = 1, #expected do
  -- every column but run_seconds and run_worker
  local a, b = expected[i]:match("^(.*),[^,]*,[^,]*$"), got[i]:match("^(.*),[^,]*,[^,]*$")
  assert(a == b, ("line %d differs:\n  local %s\n  MPI   %s"):format(i, a, b))
  workers[got[i]:match(",([^,]*)$")] = true
end
-- Rank 0's worker thread is worker 1; ranks 1 and 2 are 1001 and 2001.
assert(workers["1001"] and workers["2001"], "ranks 1 and 2 ran no rows")
support.remove_folder(folder)
print("MPI study with 3 ranks: 44 rows, identical to the local run")
