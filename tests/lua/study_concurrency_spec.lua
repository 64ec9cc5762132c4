-- Several ashlar processes on one study database: started together they
-- share the rows (claims), none fails on the schema, no row is computed
-- twice, and rows claimed by a process that died are taken over.
local ashlar = require "ashlar"
local support = require "spec_support"
local quote, run = support.quote, support.run

local ashlar_bin = assert(os.getenv("ASHLAR_BIN"), "set ASHLAR_BIN to the ashlar binary")

-- arg: db, who (a label returned as a field), log (a file each computed row
-- is appended to), rows, milliseconds of CPU per row.
local shared_script = [[
local ashlar = require "ashlar"
local db, who, log = arg[1], arg[2], arg[3]
local rows, milliseconds = tonumber(arg[4]), tonumber(arg[5])
local study = ashlar.study{
  name = "shared", db = db, workers = 2, progress = false,
  params = { i = ashlar.range(1, rows, rows) },
  run = function(p)
    local stop = os.clock() + milliseconds / 1000
    while os.clock() < stop do end
    local f = assert(io.open(log, "a"))
    f:write(("%.0f %s\n"):format(p.i, who))
    f:close()
    -- fields no row returned before: the columns are added while both run
    return { square = p.i * p.i, by = who, late = p.i > rows / 2 and p.i or nil }
  end,
}
local info = study:info()
print(("done %s ran %d elsewhere %d ok %d pending %d"):format(who, info.ran, info.elsewhere, info.ok, info.pending))
]]

-- The lines of the log, counted by row.
local function computed(path)
  local counts, total = {}, 0
  for line in support.read_file(path):gmatch("[^\n]+") do
    local i = tonumber(line:match("^(%d+) "))
    counts[i] = (counts[i] or 0) + 1
    total = total + 1
  end
  return counts, total
end

describe("ashlar.study from several processes on one database", function()
  local folder
  before_each(function()
    folder = support.temp_folder()
    support.write_file(folder .. "/shared.lua", shared_script)
  end)
  after_each(function() support.remove_folder(folder) end)

  local function start(who, rows, milliseconds)
    return ("{ %s shared.lua s.sqlite %s log %d %d > %s.out 2>&1; echo $? > %s.code; }"):format(
      quote(ashlar_bin), who, rows, milliseconds, who, who)
  end

  it("shares the rows of two processes started together: no error, each row computed once", function()
    local rows = 120
    local output, code = run(("cd %s && { %s & %s & wait; }"):format(quote(folder), start("A", rows, 20), start("B", rows, 20)))
    assert.equal(0, code, output)
    local ran, elsewhere = {}, {}
    for _, who in ipairs({ "A", "B" }) do
      local out = support.read_file(folder .. "/" .. who .. ".out")
      assert.equal("0", support.read_file(folder .. "/" .. who .. ".code"):match("%d+"), out)
      assert.is_nil(out:lower():find("error"), out)
      local r, e = out:match("done " .. who .. " ran (%d+) elsewhere (%d+) ok " .. rows .. " pending 0")
      assert.truthy(r, out)
      ran[who], elsewhere[who] = tonumber(r), tonumber(e)
      -- Every process ends with every row finished ("ok 120 pending 0"): it
      -- waited for the other's. It ran or saw run elsewhere every row that
      -- was unfinished when it opened the study (the other may have
      -- recorded some before).
      assert.is_true(ran[who] + elsewhere[who] <= rows, out)
    end
    -- How the rows split depends on when each process got going (under the
    -- sanitizers one may start after the other is done): not asserted.
    assert.equal(rows, ran.A + ran.B)

    -- Each row computed once (the log), recorded once, by the process that says it ran it.
    local counts, total = computed(folder .. "/log")
    assert.equal(rows, total)
    for i = 1, rows do assert.equal(1, counts[i], "row " .. i) end
    local study = ashlar.load_study{ db = folder .. "/s.sqlite", name = "shared" }
    local info = study:info()
    assert.same({ rows, rows, 0, 0 }, { info.rows, info.ok, info.errors, info.pending })
    local by = { A = 0, B = 0 }
    for _, row in ipairs(study:rows()) do
      by[row.by] = by[row.by] + 1
      assert.equal(row.i * row.i, row.square)
      if row.i > rows / 2 then assert.equal(row.i, row.late) else assert.is_nil(row.late) end
    end
    assert.same({ A = ran.A, B = ran.B }, by)
  end)

  it("takes over at once the rows a killed process held", function()
    local rows = 300
    local pid = run(("cd %s && { %s > /dev/null 2>&1 & echo $!; }"):format(
      quote(folder), ("%s shared.lua s.sqlite A log %d 10"):format(quote(ashlar_bin), rows))):match("%d+")
    assert.truthy(pid)
    local finished, deadline = 0, os.time() + 60
    repeat
      run("sleep 0.05")
      local ok, study = pcall(ashlar.load_study, { db = folder .. "/s.sqlite", name = "shared" })
      finished = ok and study:info().ok or 0
    until finished >= 40 or os.time() > deadline
    run("kill -9 " .. pid)
    run(("while kill -0 %s 2>/dev/null; do sleep 0.02; done"):format(pid))
    local before = ashlar.load_study{ db = folder .. "/s.sqlite", name = "shared" }:info()
    assert.is_true(before.ok >= 40 and before.ok < rows, "killed too late: " .. before.ok)

    -- The killed run's claims (rows it had taken, unfinished) hold a fresh
    -- heartbeat, but its process is gone: B takes them without waiting for
    -- the lease (60 s).
    local started = os.time()
    local output, code = run(("cd %s && %s shared.lua s.sqlite B log %d 10"):format(quote(folder), quote(ashlar_bin), rows))
    assert.equal(0, code, output)
    assert.is_true(os.time() - started < 30, "waited for the lease: " .. (os.time() - started) .. " s")
    assert.truthy(output:find(("done B ran %d elsewhere 0 ok %d pending 0"):format(rows - before.ok, rows), 1, true), output)
    local study = ashlar.load_study{ db = folder .. "/s.sqlite", name = "shared" }
    assert.same({ rows, 0 }, { study:info().ok, study:info().pending })
    -- Only the rows A was computing when killed were computed twice.
    local counts = computed(folder .. "/log")
    local twice = 0
    for i = 1, rows do
      assert.is_true(counts[i] == 1 or counts[i] == 2, "row " .. i)
      if counts[i] == 2 then twice = twice + 1 end
    end
    assert.is_true(twice <= 2, twice .. " rows computed twice")  -- A's two threads, at most
  end)

  it("takes the claims of a run whose heartbeat is older than the lease", function()
    if not run("command -v sqlite3"):find("sqlite3") then
      pending("needs the sqlite3 shell to plant a stale run")
      return
    end
    -- A run on another host, silent for two minutes, holding rows 1-20
    -- (ids 1-20 once the study's table is made).
    local output, code = run(("cd %s && %s shared.lua s.sqlite A log 1 0"):format(quote(folder), quote(ashlar_bin)))
    assert.equal(0, code, output)
    local sql = "INSERT INTO ashlar_runs(id, study, host, machine, pid, process_started, started, heartbeat)"
      .. " VALUES(1000, 'shared', 'lost-node', '', 1, 0, '2026-01-01T00:00:00Z', unixepoch('now') - 120);"
    for i = 2, 20 do sql = sql .. ("INSERT INTO ashlar_claims(study, row, run) VALUES('shared', %d, 1000);"):format(i) end
    output, code = run(("cd %s && sqlite3 s.sqlite %s"):format(quote(folder), quote(sql)))
    assert.equal(0, code, output)
    local started = os.time()
    output, code = run(("cd %s && %s shared.lua s.sqlite B log 20 0"):format(quote(folder), quote(ashlar_bin)))
    assert.equal(0, code, output)
    assert.is_true(os.time() - started < 30, "waited: " .. (os.time() - started) .. " s")
    assert.truthy(output:find("done B ran 19 elsewhere 0 ok 20 pending 0", 1, true), output)
    -- The stale run is forgotten with its claims.
    output = run(("cd %s && sqlite3 s.sqlite 'SELECT count(*) FROM ashlar_runs; SELECT count(*) FROM ashlar_claims;'"):format(quote(folder)))
    assert.equal("0\n0\n", output)
  end)
end)
