-- A study's worker threads do not change its numbers: a 2-worker study of
-- FEA runs (each factorisation ordered by METIS through CHOLMOD) stores the
-- same numbers, to the bit, in every run and as one worker does. Worker
-- threads exist only in the host running a script file, so the study runs
-- in an ashlar subprocess.
local support = require "spec_support"
local quote, run = support.quote, support.run

local ashlar_bin = assert(os.getenv("ASHLAR_BIN"), "set ASHLAR_BIN to the ashlar binary")

-- arg[1]: workers. Prints every row's stored numbers in %a (every bit).
local fea_study = [[
local workers = tonumber(arg[1])
local study = ashlar.study{
  name = "fea", workers = workers, progress = false,
  params = { k = ashlar.range(1, 24, 24) },
  run = function(p)
    local s = models.arch{ voussoirs = 8 + 4 * (p.k % 5), thickness = 0.9 + 0.002 * p.k }
    local fe = ashlar.fea(s, { refine = 3 })
    local moved, carried = 0, 0
    for _, d in ipairs(fe.displacements) do moved = moved + d[1] + 2 * d[2] + 3 * d[3] end
    for _, f in ipairs(fe.interfaces) do carried = carried + f.normal_force end
    return { status = fe.status, iterations = fe.iterations, moved = moved, carried = carried }
  end,
}
for _, row in ipairs(study:rows()) do
  print(("%d %s %d %a %a"):format(row.k, row.status, row.iterations, row.moved, row.carried))
end
print("workers", study:info().workers)
]]

describe("a study on worker threads", function()
  local folder
  before_each(function()
    folder = support.temp_folder()
    support.write_file(folder .. "/fea_study.lua", fea_study)
  end)
  after_each(function() support.remove_folder(folder) end)

  local function rows_with(workers)
    local output, code = run(("%s %s %d"):format(quote(ashlar_bin), quote(folder .. "/fea_study.lua"), workers))
    assert.equal(0, code, output)
    assert.truthy(output:find("\nworkers\t" .. workers .. "\n", 1, true), output)
    local rows = output:gsub("workers\t%d+\n$", "")
    local count = select(2, rows:gsub("\n", ""))
    assert.equal(24, count, output)
    return rows
  end

  it("stores the same FEA numbers to the bit in every run and as one worker", function()
    local one = rows_with(1)
    assert.truthy(one:find("compression_only", 1, true), one)
    for _ = 1, 2 do assert.equal(one, rows_with(2)) end
  end)
end)
