-- Parametric studies: parameter rows, recorded runs and errors, CSV, and,
-- with the host as a subprocess, worker threads and resuming after kill -9.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local quote, expect_error, run = support.quote, support.expect_error, support.run

local ashlar_bin = assert(os.getenv("ASHLAR_BIN"), "set ASHLAR_BIN to the ashlar binary")
-- The example sweep (726 analyses): arguments db, workers, csv.
local arch_sweep = support.script_folder(1) .. "/../../scripts/arch_sweep.lua"

local function by_parameters(rows, names)
  local index = {}
  for _, row in ipairs(rows) do
    local key = {}
    for _, name in ipairs(names) do key[#key + 1] = tostring(row[name]) end
    index[table.concat(key, "|")] = row
  end
  return index
end

describe("ashlar.range", function()
  it("spaces values evenly with exact ends", function()
    local values = ashlar.range(0.08, 0.20, 121)
    assert.equal(121, #values)
    assert.equal(0.08, values[1])
    assert.equal(0.20, values[121])
    support.near(values[61], 0.14, 1e-15)
  end)
  it("rejects a count below 2 for distinct ends", function()
    expect_error({"count must be at least 2"}, ashlar.range, 0, 1, 1)
    expect_error({"bad argument #3", "count"}, ashlar.range, 0, 1, 2.5)
  end)
end)

describe("ashlar.latin_hypercube", function()
  it("puts one sample in each stratum of every axis, the same for the same seed", function()
    local rows = ashlar.latin_hypercube({ t = { min = 0.1, max = 0.2 }, n = { 16, 32 } }, { samples = 20, seed = 7 })
    assert.equal(20, #rows)
    local strata, levels = {}, { [16] = 0, [32] = 0 }
    for _, row in ipairs(rows) do
      strata[math.floor((row.t - 0.1) / 0.1 * 20)] = true
      levels[row.n] = levels[row.n] + 1
    end
    local filled = 0
    for _ in pairs(strata) do filled = filled + 1 end
    assert.equal(20, filled)
    assert.same({ [16] = 10, [32] = 10 }, levels)
    assert.same(rows, ashlar.latin_hypercube({ t = { min = 0.1, max = 0.2 }, n = { 16, 32 } }, { samples = 20, seed = 7 }))
  end)
  it("names what is wrong", function()
    expect_error({"samples: missing"}, ashlar.latin_hypercube, { t = { min = 0, max = 1 } }, {})
    expect_error({"t: expected {min = a, max = b} with a <= b"}, ashlar.latin_hypercube, { t = { min = 1, max = 0 } }, { samples = 3 })
  end)
end)

describe("ashlar.study in one state", function()
  local function arch_run(p)
    local s = models.arch{ radius = 1, thickness = p.t, voussoirs = p.n }
    local r = ashlar.analyze(s, { friction = p.mu })
    return { stable = r.stable, infeasibility = r.infeasibility }
  end

  it("runs every row of a grid and matches analyses made directly", function()
    local study = ashlar.study{ name = "grid", params = { t = { 0.09, 0.12 }, n = { 8, 16 }, mu = 0.7 },
                                run = arch_run, workers = 1, progress = false }
    local info = study:info()
    assert.same({ 4, 4, 0, 0, 4 }, { info.rows, info.ok, info.errors, info.pending, info.ran })
    assert.equal(4, #study)
    local rows = by_parameters(study:rows(), { "t", "n" })
    for _, t in ipairs({ 0.09, 0.12 }) do
      for _, n in ipairs({ 8, 16 }) do
        local direct = ashlar.analyze(models.arch{ radius = 1, thickness = t, voussoirs = n }, { friction = 0.7 })
        local row = rows[tostring(t) .. "|" .. tostring(n)]
        assert.equal(direct.stable, row.stable)
        assert.equal(direct.infeasibility, row.infeasibility)
        assert.equal(0.7, row.mu)
        assert.equal("ok", row.run_status)
        assert.equal(1, row.run_worker)
      end
    end
    -- Known statics: t/R 0.12 stands with 16 voussoirs (minimum about 0.1072), 0.09 does not.
    assert.is_true(rows["0.12|16"].stable)
    assert.is_false(rows["0.09|16"].stable)
  end)

  it("records a failing run with its message and goes on", function()
    local study = ashlar.study{ name = "errors", params = { { i = 1 }, { i = 2 }, { i = 3 } }, workers = 1, progress = false,
      run = function(p)
        if p.i == 2 then error("no good: " .. p.i) end
        if p.i == 3 then return 42 end
        return { twice = 2 * p.i }
      end }
    local rows = study:rows()
    assert.equal(2, rows[1].twice)
    assert.equal("error", rows[2].run_status)
    assert.truthy(rows[2].run_error:find("no good: 2", 1, true))
    assert.truthy(rows[2].run_error:find("study_spec.lua:%d+:"))
    assert.equal("run returned a number, expected a table of fields", rows[3].run_error)
    assert.same({ ok = 1, errors = 2 }, { ok = study:info().ok, errors = study:info().errors })
  end)

  it("turns bad fields into error rows", function()
    local study = ashlar.study{ name = "fields", params = { i = { 1, 2, 3, 4 } }, workers = 1, progress = false,
      run = function(p)
        if p.i == 1 then return { nested = {} } end
        if p.i == 2 then return { i = 5 } end
        if p.i == 3 then return { ["not a name"] = 1 } end
        return { 7 }
      end }
    local rows = study:rows()
    assert.equal("field 'nested' is a table: numbers, booleans or strings are allowed", rows[1].run_error)
    assert.equal("returned field 'i' is a parameter", rows[2].run_error)
    assert.truthy(rows[3].run_error:find("'not a name' is not a column name", 1, true))
    assert.equal("run returned a field with a number key", rows[4].run_error)
  end)

  it("writes CSV with a header and one line per row", function()
    local folder = support.temp_folder()
    local study = ashlar.study{ name = "csv", params = { x = { 1, 2 }, label = "a,b" }, workers = 1, progress = false,
      run = function(p) return { y = p.x / 4, flag = p.x > 1 } end }
    study:csv(folder .. "/out.csv")
    assert.equal('label,x,flag,y,run_status,run_error,run_seconds,run_worker\r\n', support.read_file(folder .. "/out.csv"):match("^[^\n]*\n"))
    local lines = {}
    for line in support.read_file(folder .. "/out.csv"):gmatch("[^\r\n]+") do lines[#lines + 1] = line end
    assert.equal(3, #lines)
    assert.truthy(lines[2]:find('^"a,b",1,false,0.25,ok,,'))
    assert.truthy(lines[3]:find('^"a,b",2,true,0.5,ok,,'))
    support.remove_folder(folder)
  end)

  it("takes math.huge as a parameter: kept, reopened, written and charted", function()
    local folder = support.temp_folder()
    local calls = 0
    local function run_it(p) calls = calls + 1; return { infeasibility = p.mu == math.huge and 0 or 0.2 / p.mu } end
    local db = folder .. "/mu.sqlite"
    local study = ashlar.study{ name = "mu", params = { mu = { 0.2, 0.5, math.huge } }, run = run_it, db = db,
                                workers = 1, progress = false }
    local rows = study:rows()
    assert.equal(math.huge, rows[3].mu)
    assert.equal(0, rows[3].infeasibility)
    ashlar.study{ name = "mu", params = { mu = { 0.2, 0.5, math.huge } }, run = run_it, db = db, workers = 1, progress = false }
    assert.equal(3, calls)  -- the reopened study found all three, math.huge included
    study:csv(folder .. "/mu.csv")
    local text = support.read_file(folder .. "/mu.csv")
    assert.truthy(text:find("\n0.2,1,", 1, true))  -- shortest numbers: 0.2, not 0.20000000000000001
    assert.truthy(text:find("\ninf,0,", 1, true))
    -- Charted against mu, math.huge has no place on the axis: skipped, counted.
    local chart = study:chart{ path = folder .. "/mu.png", x = "mu", y = "infeasibility" }
    assert.equal(1, chart.skipped)
    assert.equal(2, chart.series[1].points)
    expect_error({ "is NaN" }, ashlar.study, { name = "nan", params = { mu = { 0 / 0 } }, run = run_it,
                                             workers = 1, progress = false })
    support.remove_folder(folder)
  end)

  it("keeps results in a database and runs only new rows when reopened", function()
    local folder = support.temp_folder()
    local calls = 0
    local function run_it(p) calls = calls + 1; return { y = p.x * p.x } end
    ashlar.study{ name = "grow", params = { x = { 1, 2, 3 } }, run = run_it, db = folder .. "/s.sqlite", workers = 1, progress = false }
    local study = ashlar.study{ name = "grow", params = { x = { 1, 2, 3, 4 } }, run = run_it, db = folder .. "/s.sqlite", workers = 1, progress = false }
    assert.equal(4, calls)
    assert.equal(1, study:info().ran)
    local loaded = ashlar.load_study{ db = folder .. "/s.sqlite", name = "grow" }
    assert.equal(4, #loaded)
    assert.equal(16, loaded:rows()[4].y)
    expect_error({"has the parameters (x), this one (z)"}, ashlar.study,
      { name = "grow", params = { z = { 1 } }, run = run_it, db = folder .. "/s.sqlite", workers = 1, progress = false })
    support.remove_folder(folder)
  end)

  it("names what is wrong with its options", function()
    local run_it = function() return {} end
    expect_error({"name: a study needs a name"}, ashlar.study, { params = { x = 1 }, run = run_it })
    expect_error({"must be 1 to 64 letters, digits, _ or -"}, ashlar.study, { name = "a b", params = { x = 1 }, run = run_it })
    expect_error({"params: missing"}, ashlar.study, { name = "a", run = run_it })
    expect_error({'run: expected a function or a string "module.function", got nil'}, ashlar.study, { name = "a", params = { x = 1 } })
    expect_error({"params.x[2] is a table"}, ashlar.study, { name = "a", params = { x = { 1, {} } }, run = run_it })
    expect_error({"params: rows 1 and 2 are the same"}, ashlar.study, { name = "a", params = { { x = 1 }, { x = 1.0 } }, run = run_it, workers = 1 })
    expect_error({"params[2] has other parameters than params[1]"}, ashlar.study, { name = "a", params = { { x = 1 }, { y = 1 } }, run = run_it })
    expect_error({"params: 'run_status' is a run column"}, ashlar.study, { name = "a", params = { run_status = 1 }, run = run_it })
    expect_error({"workers: expected 0 (all cores) or a number of workers"}, ashlar.study, { name = "a", params = { x = 1 }, run = run_it, workers = -1 })
    expect_error({"unknown option 'worker'"}, ashlar.study, { name = "a", params = { x = 1 }, run = run_it, worker = 2 })
    expect_error({"no study 'nothing'"}, ashlar.load_study, { db = ":memory:", name = "nothing" })
  end)

  it("reports the MPI rank and size outside a job as 0 and 1", function()
    assert.same({ 0, 1 }, { ashlar.rank() })
  end)
end)

describe("ashlar.study with the host", function()
  local folder
  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  it("gives the same table with 2 worker threads as with 1", function()
    local command = "cd " .. quote(folder) .. " && " .. quote(ashlar_bin) .. " " .. quote(arch_sweep)
    local out1, code1 = run(command .. " one.sqlite 1 one.csv")
    local out2, code2 = run(command .. " two.sqlite 2 two.csv")
    assert.equal(0, code1, out1)
    assert.equal(0, code2, out2)
    assert.truthy(out1:find("runs 726 seconds [%d.]+ runs_per_second [%d.]+ workers 1 errors 0"), out1)
    assert.truthy(out2:find("runs 726 seconds [%d.]+ runs_per_second [%d.]+ workers 2 errors 0"), out2)
    local function results(csv)  -- every column but run_seconds and run_worker
      local lines = {}
      for line in support.read_file(csv):gmatch("[^\r\n]+") do lines[#lines + 1] = line:match("^(.*),[^,]*,[^,]*$") end
      return lines
    end
    assert.same(results(folder .. "/one.csv"), results(folder .. "/two.csv"))
    assert.equal(727, #results(folder .. "/two.csv"))
  end)

  it("resumes after kill -9 with every finished row kept once", function()
    support.write_file(folder .. "/slow.lua", [[
local ashlar = require "ashlar"
local study = ashlar.study{
  name = "slow", db = arg[1], workers = 2, log_interval = 0.05,
  params = { i = ashlar.range(1, 300, 300) },
  run = function(p)
    local stop = os.clock() + 0.01
    while os.clock() < stop do end
    return { square = p.i * p.i }
  end,
}
print("ran " .. study:info().ran)
]])
    local db = folder .. "/slow.sqlite"
    local pid = run(("cd %s && { %s slow.lua slow.sqlite > first.log 2>&1 & echo $!; }"):format(quote(folder), quote(ashlar_bin))):match("%d+")
    assert.truthy(pid)
    local finished = 0
    local deadline = os.time() + 60
    repeat
      run("sleep 0.05")
      local ok, study = pcall(ashlar.load_study, { db = db, name = "slow" })
      finished = ok and study:info().ok or 0
    until finished >= 60 or os.time() > deadline
    run("kill -9 " .. pid)
    run(("while kill -0 %s 2>/dev/null; do sleep 0.02; done"):format(pid))
    local before = ashlar.load_study{ db = db, name = "slow" }:info()
    assert.is_true(before.ok >= 60 and before.ok < 300, "killed too late: " .. before.ok)
    assert.equal(300, before.rows)

    local output, code = run(("cd %s && %s slow.lua slow.sqlite"):format(quote(folder), quote(ashlar_bin)))
    assert.equal(0, code, output)
    assert.truthy(output:find("ran " .. (300 - before.ok), 1, true), output)  -- only the unfinished rows ran
    local after = ashlar.load_study{ db = db, name = "slow" }
    assert.same({ 300, 300, 0 }, { #after, after:info().ok, after:info().pending })
    local seen = {}
    for _, row in ipairs(after:rows()) do
      assert.is_nil(seen[row.i], "duplicate row " .. row.i)
      seen[row.i] = true
      assert.equal(row.i * row.i, row.square)
    end
  end)

  it("says why when a worker cannot reach the study", function()
    support.write_file(folder .. "/hidden.lua", [[
local ashlar = require "ashlar"
-- Worker states run the script again: this one stops before the study
-- when the marker file the script's first run made exists.
local marker = io.open("marker")
if marker then marker:close() return end
assert(io.open("marker", "w")):close()
ashlar.study{ name = "hidden", workers = 2, params = { x = { 1, 2, 3 } }, run = function(p) return { y = p.x } end }
]])
    local output, code = run(("cd %s && %s hidden.lua"):format(quote(folder), quote(ashlar_bin)))
    assert.is_not.equal(0, code)
    -- Either thread may fail first.
    assert.truthy(output:find("no worker left to run the 3 remaining rows; worker [12] could not start: the script "), output)
    assert.truthy(output:find("ended without reaching ashlar.study{name = 'hidden'}", 1, true), output)
  end)
end)
