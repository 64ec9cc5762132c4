-- ashlar.study{ run = "module.function" }: worker states require the module
-- instead of running the script again; a bad module or function is the
-- call's error, before the store opens or a worker starts; a sandboxed
-- script's require stays restricted. The rows are boxes (fixtures/study_run)
-- whose mass and volume have closed forms.
local ashlar = require "ashlar"
local support = require "spec_support"
local quote, expect_error, run = support.quote, support.expect_error, support.run

local ashlar_bin = assert(os.getenv("ASHLAR_BIN"), "set ASHLAR_BIN to the ashlar binary")
local fixtures = support.script_folder(1) .. "/fixtures"
local box_study = fixtures .. "/study_run/box_study.lua"
local BOXES = { a = { 0.5, 1, 1.5, 2 }, b = { 0.25, 0.75, 3 }, c = { 1, 2 } }

-- Every row ran and its numbers are the closed forms of its parameters.
local function check_boxes(rows)
  assert.equal(24, #rows)
  for _, row in ipairs(rows) do
    assert.equal("ok", row.run_status, row.run_error)
    local volume = row.a * row.b * row.c
    support.near(row.volume, volume, 1e-12 * volume, "volume")
    support.near(row.mass, 2400 * volume, 1e-12 * 2400 * volume, "mass")
  end
end

local function count_lines(path, word)
  local file = io.open(path)
  if not file then return 0 end
  local count = 0
  for line in file:lines() do count = count + (line == word and 1 or 0) end
  file:close()
  return count
end

local function exists(path)
  local file = io.open(path)
  if file then file:close() end
  return file ~= nil
end

describe("run = \"module.function\" in this state", function()
  local saved_path
  before_each(function()
    saved_path = package.path
    package.path = fixtures .. "/study_run/?.lua;" .. fixtures .. "/?.lua;" .. package.path
  end)
  after_each(function() package.path = saved_path end)

  it("runs the module's function on 2 worker threads, even under busted", function()
    -- A function run would need workers = 1 here: its workers would run busted again.
    local study = ashlar.study{ name = "boxes", params = BOXES, run = "box_rows.mass", workers = 2, progress = false }
    check_boxes(study:rows())
    for _, row in ipairs(study:rows()) do assert.truthy(row.run_worker == 1 or row.run_worker == 2) end
    assert.same({ 24, 0 }, { study:info().ok, study:info().errors })
  end)

  it("splits at the last dot: a.b.c is the function c of the module a.b", function()
    local study = ashlar.study{ name = "dotted", params = BOXES, run = "study_run.box_rows.mass", workers = 2,
                                progress = false }
    check_boxes(study:rows())
  end)

  it("runs in the calling state with workers = 1, as a function run does", function()
    local direct = ashlar.study{ name = "direct", params = BOXES, run = require("box_rows").mass, workers = 1,
                                 progress = false }
    local module = ashlar.study{ name = "module", params = BOXES, run = "box_rows.mass", workers = 1, progress = false }
    check_boxes(module:rows())
    assert.same(direct:rows()[7].mass, module:rows()[7].mass)
  end)

  it("names the option and the value when the module or the function is wrong, before any worker starts", function()
    local folder = support.temp_folder()
    package.path = folder .. "/?.lua;" .. package.path
    support.write_file(folder .. "/broken.lua", 'error("cannot load me")\n')
    support.write_file(folder .. "/nothing.lua", "local unused = 1\n")
    local db = folder .. "/never.sqlite"
    local function study(run_it)
      return ashlar.study{ name = "bad", params = BOXES, run = run_it, workers = 2, db = db, progress = false }
    end
    expect_error({ "bad argument #1", 'run: "no_such_module.mass": require "no_such_module" failed: ',
                   "module 'no_such_module' not found" }, study, "no_such_module.mass")
    expect_error({ 'run: "box_rows.volume_of": module \'box_rows\' has no function \'volume_of\'' },
                 study, "box_rows.volume_of")
    expect_error({ 'run: "box_rows.density": module \'box_rows\' has a number value, not a function, at \'density\'' },
                 study, "box_rows.density")
    expect_error({ 'run: "broken.f": require "broken" failed: ', "broken.lua:1: cannot load me" }, study, "broken.f")
    expect_error({ 'run: "nothing.f": require "nothing" gave a boolean value, not a table holding the function \'f\'' },
                 study, "nothing.f")
    for _, text in ipairs({ "mass", "box_rows.", ".mass", "a..mass", "" }) do
      expect_error({ 'run: expected a function or a string "module.function" (the function of a module that require finds), got "'
                     .. text .. '"' }, study, text)
    end
    expect_error({ 'run: expected a function or a string "module.function", got number' }, study, 7)
    expect_error({ 'run: expected a function or a string "module.function", got nil' }, study, nil)
    -- The store never opened: no row was handed to any worker.
    assert.is_false(exists(db))
    support.remove_folder(folder)
  end)
end)

describe("run = \"module.function\" with the host", function()
  local folder
  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  local function run_box_study(form, workers)
    local command = ("cd %s && ASHLAR_STUDY_LOG=%s.log %s %s %s.sqlite %d %s"):format(
      quote(folder), form, quote(ashlar_bin), quote(box_study), form, workers, form)
    local output, code = run(command)
    assert.equal(0, code, output)
    assert.truthy(output:find("rows 24 ok 24 errors 0", 1, true), output)
    local log = folder .. "/" .. form .. ".log"
    return count_lines(log, "script"), count_lines(log, "module")
  end

  it("runs the script once and loads the module once per state; the function form runs the script per worker", function()
    -- The module is beside the script, not in the current folder: found on
    -- the script's folder, which the host puts first on package.path.
    local scripts, modules = run_box_study("module", 3)
    assert.equal(1, scripts)   -- the calling state only
    assert.equal(4, modules)   -- the calling state and the 3 worker states
    local fallback_scripts, fallback_modules = run_box_study("function", 3)
    assert.equal(4, fallback_scripts)  -- the calling state, then every worker state runs it again
    assert.equal(4, fallback_modules)
    local module_rows = ashlar.load_study{ db = folder .. "/module.sqlite", name = "boxes" }:rows()
    local function_rows = ashlar.load_study{ db = folder .. "/function.sqlite", name = "boxes" }:rows()
    check_boxes(module_rows)
    check_boxes(function_rows)
    local workers = {}
    for i, row in ipairs(module_rows) do
      assert.equal(function_rows[i].mass, row.mass)
      workers[row.run_worker] = true
    end
    assert.is_nil(workers[4])
  end)

  it("finds a module in the current folder (./?.lua of Lua's default path)", function()
    assert(os.execute("mkdir " .. quote(folder .. "/scripts")))
    support.write_file(folder .. "/here_rows.lua", "return { square = function(p) return { y = p.x * p.x } end }\n")
    support.write_file(folder .. "/scripts/here.lua", [[
local ashlar = require "ashlar"
local study = ashlar.study{ name = "here", params = { x = { 1, 2, 3, 4 } }, run = "here_rows.square", workers = 2,
                            progress = false }
local sum = 0
for _, row in ipairs(study:rows()) do sum = sum + row.y end
print("sum " .. sum)
]])
    local output, code = run(("cd %s && %s scripts/here.lua"):format(quote(folder), quote(ashlar_bin)))
    assert.equal(0, code, output)
    assert.truthy(output:find("sum 30", 1, true), output)
  end)

  it("says why when a worker state cannot load the module the calling state loaded", function()
    support.write_file(folder .. "/needs_setup.lua", [[
assert(SET_UP, "needs_setup: the global SET_UP is missing")
return { f = function(p) return { y = p.x } end }
]])
    support.write_file(folder .. "/setup.lua", [[
local ashlar = require "ashlar"
SET_UP = true  -- a global of the script's state: worker states do not run the script
ashlar.study{ name = "setup", params = { x = { 1, 2, 3 } }, run = "needs_setup.f", workers = 2, progress = false }
]])
    local output, code = run(("cd %s && %s setup.lua"):format(quote(folder), quote(ashlar_bin)))
    assert.is_not.equal(0, code)
    assert.truthy(output:find("no worker left to run the 3 remaining rows; worker [12] could not start: " ..
                              'run = "needs_setup.f": ', 1), output)
    assert.truthy(output:find("needs_setup: the global SET_UP is missing", 1, true), output)
  end)

  it("gives worker threads to a script run by stock lua5.4 with the C module", function()
    local module_dir = assert(os.getenv("ASHLAR_MODULE_DIR"), "set ASHLAR_MODULE_DIR to the folder of ashlar.so")
    support.write_file(folder .. "/stock.lua", ([[
package.cpath = %q .. "/?.so;" .. package.cpath
package.path = %q .. "/?.lua;" .. package.path
local ashlar = require "ashlar"
local study = ashlar.study{ name = "stock", params = { a = { 1, 2 }, b = { 1, 3 }, c = 0.5 }, run = "box_rows.mass",
                            workers = 2, progress = false }
local workers = {}
for _, row in ipairs(study:rows()) do
  assert(row.run_status == "ok", row.run_error)
  assert(math.abs(row.mass - 2400 * row.a * row.b * row.c) < 1e-9)
  workers[row.run_worker] = true
end
print("ok " .. study:info().ok)
]]):format(module_dir, fixtures .. "/study_run"))
    local output, code = run(("cd %s && lua5.4 stock.lua"):format(quote(folder)))
    assert.equal(0, code, output)
    assert.truthy(output:find("ok 4", 1, true), output)
  end)
end)

describe("run = \"module.function\" in a sandbox", function()
  local folder
  before_each(function()
    folder = support.temp_folder()
    assert(os.execute("mkdir " .. quote(folder .. "/allowed") .. " " .. quote(folder .. "/secret")))
    local module = "return { f = function(p) return { y = 3 * p.x } end }\n"
    support.write_file(folder .. "/allowed/open_rows.lua", module)
    support.write_file(folder .. "/secret/secret_rows.lua", module)
  end)
  after_each(function() support.remove_folder(folder) end)

  local function sandboxed_study(module)
    return ashlar.sandbox{ read = { folder .. "/allowed" }, source = ([[
package.path = %q .. "/allowed/?.lua;" .. %q .. "/secret/?.lua;" .. package.path
local ashlar = require "ashlar"
local study = ashlar.study{ name = "s", params = { x = { 1, 2, 3, 4 } }, run = %q, workers = 2, progress = false }
local sum = 0
for _, row in ipairs(study:rows()) do sum = sum + row.y end
return sum, study:info().errors
]]):format(folder, folder, module .. ".f") }
  end

  it("requires a module in an allowed folder, in sandboxed worker states", function()
    local outcome = sandboxed_study("open_rows")
    assert.equal("ok", outcome.status, outcome.message)
    assert.same({ 30, 0 }, outcome.results)
  end)

  it("refuses a module outside the allowed folders, naming why", function()
    local outcome = sandboxed_study("secret_rows")
    assert.equal("error", outcome.status)
    assert.truthy(outcome.message:find('run: "secret_rows.f": require "secret_rows" failed: ' ..
                                       "module 'secret_rows' not found", 1, true), outcome.message)
    assert.truthy(outcome.message:find(folder .. "/secret/secret_rows.lua' (outside the sandbox)", 1, true),
                  outcome.message)
  end)

  it("runs the module form under ashlar --sandbox with the module beside the script", function()
    assert(os.execute("cp " .. quote(fixtures .. "/study_run/box_rows.lua") .. " " .. quote(folder .. "/allowed/box_rows.lua")))
    support.write_file(folder .. "/allowed/sandboxed.lua", [[
local ashlar = require "ashlar"
local study = ashlar.study{ name = "boxes", params = { a = { 1, 2 }, b = { 1, 3 }, c = 0.5 }, run = "box_rows.mass",
                            workers = 2, progress = false }
print("ok " .. study:info().ok .. " errors " .. study:info().errors)
]])
    local output, code = run(("cd %s && %s --sandbox allowed/sandboxed.lua"):format(quote(folder), quote(ashlar_bin)))
    assert.equal(0, code, output)
    assert.truthy(output:find("ok 4 errors 0", 1, true), output)
  end)
end)
