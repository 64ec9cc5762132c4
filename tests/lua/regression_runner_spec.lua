-- `ashlar test`, the regression runner, run as a subprocess on suites made
-- in a temporary folder: golden values written by --update and checked by
-- the next run, failures and their messages, references that no update can
-- override, stale values, script errors and bad input.
local ashlar_bin = assert(os.getenv("ASHLAR_BIN"), "set ASHLAR_BIN to the ashlar binary")

local support = require "spec_support"
local quote, write_file, read_file = support.quote, support.write_file, support.read_file
local run = support.run

local function escape_pattern(text)
  return (text:gsub("%p", "%%%0"))
end

local function last_line(output)
  return output:match("([^\n]*)\n$")
end

-- Whether `line` is one of the output's lines.
local function has_line(output, line)
  return ("\n" .. output):find("\n" .. line .. "\n", 1, true) ~= nil
end

local HEADER = 'local check = require "ashlar.regression"\n'

describe("ashlar test", function()
  local folder

  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  local function script(name, body)
    write_file(folder .. "/" .. name, HEADER .. body)
    return folder .. "/" .. name
  end

  local function ashlar_test(arguments)
    return run(quote(ashlar_bin) .. " test " .. (arguments or "") .. " " .. quote(folder))
  end

  local function golden_text()
    return read_file(folder .. "/golden.json")
  end

  local function golden_exists()
    local file = io.open(folder .. "/golden.json")
    if file then file:close() end
    return file ~= nil
  end

  -- Two scripts with every kind of value, the second with a reference.
  local function typical_suite()
    script("a_numbers.lua", [[
check("pi", math.pi)
check("list", { 1, 2.5, 1 / 3 })
check("flag", true)
check("label", "optimal")
]])
    script("b_reference.lua", [[
check("closed form", 0.5 * 0.5, { reference = 0.25, reference_tolerance = 1e-12 })
]])
  end

  describe("golden values", function()
    it("fails every check without them, writes them with --update, then passes", function()
      typical_suite()
      local output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.are.equal("0 passed, 5 failed", last_line(output))
      assert.is_true(has_line(output, "  FAIL " .. folder .. '/a_numbers.lua:2: "pi": no golden value (run `ashlar test --update`)'), output)
      assert.is_false(golden_exists())

      output, code = ashlar_test("--update")
      assert.are.equal(0, code, output)
      assert.are.equal("5 passed, 0 failed", last_line(output))
      assert.is_true(has_line(output, '  added "pi": 3.141592653589793'), output)
      assert.is_true(has_line(output, "wrote " .. folder .. "/golden.json: 5 added, 0 changed, 0 removed"), output)
      -- Sorted keys, one value per line, 17 significant digits.
      assert.are.equal([[
{
  "a_numbers.lua": {
    "flag": true,
    "label": "optimal",
    "list": [
      1,
      2.5,
      0.33333333333333331
    ],
    "pi": 3.1415926535897931
  },
  "b_reference.lua": {
    "closed form": 0.25
  }
}
]], golden_text())

      output, code = ashlar_test()
      assert.are.equal(0, code, output)
      assert.are.equal("5 passed, 0 failed", last_line(output))
      assert.matches("\na_numbers%.lua: 4 checks, %d+%.%d%d s\nb_reference%.lua: 1 checks, ", "\n" .. output)

      output, code = ashlar_test("--update")
      assert.are.equal(0, code)
      assert.is_true(has_line(output, folder .. "/golden.json: no change"), output)
    end)

    it("reports a changed value with file:line, name, golden, got, relative difference and tolerance", function()
      typical_suite()
      assert.are.equal(0, select(2, ashlar_test("--update")))
      script("a_numbers.lua", [[
check("pi", 3.14)
check("list", { 1, 2.5, 0.3 }, { tolerance = 1e-3 })
check("flag", false)
check("label", 7)
]])
      local output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.are.equal("1 passed, 4 failed", last_line(output))
      local path = folder .. "/a_numbers.lua"
      for _, line in ipairs{
        path .. ':2: "pi": golden 3.141592653589793, got 3.14: relative difference 0.000507 > tolerance 1e-09',
        path .. ':3: "list": element 3 of 3: golden 0.3333333333333333, got 0.3: relative difference 0.1 > tolerance 0.001',
        path .. ':4: "flag": golden true, got false',
        path .. ':5: "label": golden "optimal" (a string), got 7 (a number)',
      } do
        assert.is_true(has_line(output, "  FAIL " .. line), line .. "\nnot in:\n" .. output)
      end

      output, code = ashlar_test("--update")
      assert.are.equal(0, code)
      assert.is_true(has_line(output, '  changed "pi": 3.141592653589793 -> 3.14'), output)
      assert.is_true(has_line(output, '  changed "label": "optimal" -> 7'), output)
      assert.is_true(has_line(output, "wrote " .. folder .. "/golden.json: 0 added, 4 changed, 0 removed"), output)
      assert.matches('"pi": 3.1400000000000001\n', golden_text())
      assert.are.equal("5 passed, 0 failed", last_line((ashlar_test())))
    end)

    it("passes a value within its tolerance, and --update keeps the golden one", function()
      script("close.lua", "check('x', 1.0)\ncheck('y', 0.0)\n")
      assert.are.equal(0, select(2, ashlar_test("--update")))
      local written = golden_text()
      script("close.lua", "check('x', 1.0 + 1e-12)\ncheck('y', 1e-13, { absolute = 1e-12 })\n")
      local output, code = ashlar_test()
      assert.are.equal(0, code, output)
      output, code = ashlar_test("--update")
      assert.are.equal(0, code)
      assert.is_true(has_line(output, folder .. "/golden.json: no change"), output)
      assert.are.equal(written, golden_text())

      script("close.lua", "check('x', 1.0 + 1e-8)\ncheck('y', 1e-11, { absolute = 1e-12 })\n")
      output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.are.equal("0 passed, 2 failed", last_line(output))
      assert.matches('"y": golden 0, got 1e%-11: relative difference inf, difference 1e%-11 > tolerance 1e%-09, absolute 1e%-12', output)
    end)

    it("never writes a value that misses its reference, and still fails", function()
      script("reference.lua", [[
check("in", 0.1072, { reference = 0.1072, reference_absolute = 5e-4 })
check("out", 0.2, { reference = 0.1072, reference_tolerance = 5e-3 })
check("list", { 1, 2 }, { reference = { 1, 2.5 }, reference_tolerance = 0.1 })
check("status", "unbounded", { reference = "optimal" })
]])
      local output, code = ashlar_test("--update")
      assert.are.equal(1, code)
      assert.are.equal("1 passed, 3 failed", last_line(output))
      local path = folder .. "/reference.lua"
      for _, line in ipairs{
        path .. ':3: "out": reference 0.1072, got 0.2: relative difference 0.866 > reference_tolerance 0.005 (not written)',
        path .. ':4: "list": element 2 of 2: reference 2.5, got 2: relative difference 0.2 > reference_tolerance 0.1 (not written)',
        path .. ':5: "status": reference "optimal", got "unbounded" (not written)',
      } do
        assert.is_true(has_line(output, "  FAIL " .. line), line .. "\nnot in:\n" .. output)
      end
      assert.are.equal('{\n  "reference.lua": {\n    "in": 0.1072\n  }\n}\n', golden_text())

      -- Nor does a golden value edited by hand make it pass.
      write_file(folder .. "/golden.json", '{ "reference.lua": { "in": 0.1072, "out": 0.2, "list": [1, 2], "status": "unbounded" } }')
      output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.are.equal("1 passed, 3 failed", last_line(output))
      assert.matches('"out": reference 0.1072, got 0.2: relative difference 0.866 > reference_tolerance 0.005\n', output)
    end)

    it("reports stale golden values, of a check or of a whole script, and --update removes them", function()
      typical_suite()
      assert.are.equal(0, select(2, ashlar_test("--update")))
      script("a_numbers.lua", 'check("pi", math.pi)\ncheck("flag", true)\ncheck("label", "optimal")\n')
      os.remove(folder .. "/b_reference.lua")
      local output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.are.equal("3 passed, 2 failed", last_line(output))
      local golden = folder .. "/golden.json"
      assert.is_true(has_line(output, "  FAIL " .. golden .. ': "a_numbers.lua" / "list": stale golden value [1, 2.5, 0.3333333333333333], the script no longer records it (run `ashlar test --update` to remove it)'), output)
      assert.is_true(has_line(output, "  FAIL " .. golden .. ': "b_reference.lua" / "closed form": stale golden value 0.25, there is no such script (run `ashlar test --update` to remove it)'), output)

      output, code = ashlar_test("--update")
      assert.are.equal(0, code)
      assert.is_true(has_line(output, '  removed "list": [1, 2.5, 0.3333333333333333]'), output)
      assert.is_true(has_line(output, '  removed "closed form": 0.25'), output)
      assert.is_true(has_line(output, "wrote " .. golden .. ": 0 added, 0 changed, 2 removed"), output)
      assert.are.equal("3 passed, 0 failed", last_line((ashlar_test())))
    end)
  end)

  describe("script errors", function()
    it("count as one failure each, with file:line and a traceback, and keep the script's golden values", function()
      script("broken.lua", 'check("first", 1)\ncheck("second", 2)\n')
      assert.are.equal(0, select(2, ashlar_test("--update")))
      local path = script("broken.lua", 'check("first", 1)\nlocal function fail() error("boom") end\nfail()\n')
      script("syntax.lua", "check('x',\n")
      for _, update in ipairs{ "", "--update" } do
        local output, code = ashlar_test(update)
        assert.are.equal(1, code)
        assert.are.equal("1 passed, 2 failed", last_line(output))
        assert.matches("\n  ERROR " .. escape_pattern(path) .. ":3: boom\n      stack traceback:\n", output)
        assert.matches(escape_pattern(path) .. ":4: in main chunk", output)
        assert.matches("\n  ERROR " .. escape_pattern(folder) .. "/syntax%.lua:3: unexpected symbol near <eof>\n", output)
        -- "second" was not reached: it is not stale.
        assert.is_nil(output:find("stale", 1, true))
      end
      assert.matches('"second": 2', golden_text())
    end)

    it("include a duplicate check name and a value that is not finite, at the script's line", function()
      local path = script("bad.lua", 'check("x", 1)\ncheck("x", 2)\n')
      local output = ashlar_test()
      assert.matches("ERROR " .. escape_pattern(path) .. ':3: check "x" recorded twice %(first at '
                     .. escape_pattern(path) .. ":2%): names must be unique within a script\n", output)
      for value, shown in pairs{ ["0/0"] = "nan", ["math.huge"] = "inf", ["{ 1, -math.huge }"] = "-inf" } do
        script("bad.lua", ("check(\"x\", %s)\n"):format(value))
        output = ashlar_test()
        assert.matches(escape_pattern(path) .. ":2: bad argument #2 to 'check' %(\"x\"[%[%]%d]*: expected a finite number, got "
                       .. escape_pattern(shown) .. " %(golden values are finite: record a status or a boolean instead%)%)", output)
        assert.are.equal("0 passed, 1 failed", last_line(output))
      end
    end)

    it("include bad arguments to check, naming what is allowed", function()
      local cases = {
        { "check('x')", "bad argument #2 to 'check' (\"x\": expected a number, boolean, string or list of numbers, got no value)" },
        { "check('', 1)", "bad argument #1 to 'check' (name: expected a non-empty string)" },
        { "check('x', { 1, 'a' })", "bad argument #2 to 'check' (\"x\"[2]: expected a number, got string)" },
        { "check('x', { 1, y = 2 })", "bad argument #2 to 'check' (\"x\": expected a list of numbers, got a table with keys other than 1..1)" },
        { "check('x', 1, { tolerence = 1 })", "bad argument #3 to 'check' (unknown option 'tolerence' (allowed: absolute, reference, reference_absolute, reference_tolerance, tolerance))" },
        { "check('x', 1, { tolerance = -1 })", "bad argument #3 to 'check' (tolerance: expected a number >= 0, got -1" },
        { "check('x', 'a', { tolerance = 1 })", "bad argument #3 to 'check' (tolerance and absolute: only for numbers, the value is a string)" },
        { "check('x', 1, { reference = 1 })", "bad argument #3 to 'check' (reference: give reference_tolerance (relative) or reference_absolute, or both)" },
        { "check('x', 1, { reference = 'a' })", "bad argument #3 to 'check' (reference: expected a number like the value, got a string)" },
        { "check('x', { 1 }, { reference = { 1, 2 }, reference_tolerance = 1 })", "bad argument #3 to 'check' (reference: has 2 numbers, the value 1)" },
        { "check('x', 1, { reference_tolerance = 1 })", "bad argument #3 to 'check' (reference_tolerance and reference_absolute: only with a reference)" },
      }
      for _, case in ipairs(cases) do
        local path = script("bad.lua", case[1] .. "\n")
        local output, code = ashlar_test()
        assert.are.equal(1, code)
        assert.is_truthy(output:find(path .. ":2: " .. case[2], 1, true), case[2] .. "\nnot in:\n" .. output)
      end
    end)

    it("include os.exit, which would otherwise end the run with the script's status", function()
      local path = script("exits.lua", "check('x', 1)\nos.exit(0)\n")
      script("later.lua", "check('y', 2)\n")
      local output, code = ashlar_test("--update")
      assert.are.equal(1, code)
      assert.matches("\n  ERROR " .. escape_pattern(path) .. ":3: os%.exit: a check script cannot end the run "
                     .. "%(raise an error to fail it%)\n", output)
      -- A script that failed writes nothing: its "x" has no golden value.
      assert.are.equal("1 passed, 2 failed", last_line(output))
    end)

    it("include a crash of the script's process, which fails that script alone", function()
      -- The shell's parent is the process running the script.
      script("crashes.lua", "check('x', 1)\nos.execute('kill -KILL $PPID')\n")
      script("later.lua", "check('y', 2)\n")
      local output, code = ashlar_test("--update")
      assert.are.equal(1, code)
      assert.is_true(has_line(output, "  ERROR " .. folder .. "/crashes.lua: its process was killed by signal 9 "
                                      .. "(Killed) before it handed back a result"), output)
      assert.is_true(has_line(output, '  added "y": 2'), output)
      assert.are.equal("1 passed, 1 failed", last_line(output))
    end)

    it("fail a script that records no checks", function()
      local path = script("empty.lua", "local unused = 1\n")
      local output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.is_true(has_line(output, "  FAIL " .. path .. ': records no checks (call the function that `require "ashlar.regression"` returns)'), output)
      assert.are.equal("0 passed, 1 failed", last_line(output))
    end)
  end)

  describe("bad input", function()
    it("says so for a missing folder, a folder without scripts and an unknown option", function()
      local output, code = run(quote(ashlar_bin) .. " test " .. quote(folder .. "/missing"))
      assert.are.equal(1, code)
      assert.are.equal("ashlar: test: no such folder '" .. folder .. "/missing'\n", output)

      output, code = ashlar_test()
      assert.are.equal(1, code)
      assert.are.equal("ashlar: test: no check scripts (*.lua) in '" .. folder .. "'\n", output)

      script("a.lua", "check('x', 1)\n")
      output, code = run(quote(ashlar_bin) .. " test " .. quote(folder .. "/a.lua"))
      assert.are.equal(1, code)
      assert.are.equal("ashlar: test: '" .. folder .. "/a.lua' is not a folder\n", output)

      output, code = ashlar_test("--frobnicate")
      assert.are.equal(1, code)
      assert.matches("^ashlar: test: unrecognized option '%-%-frobnicate'\nusage: ashlar test", output)

      output, code = run(quote(ashlar_bin) .. " test -- " .. quote(folder) .. " nothing_like_it")
      assert.are.equal(1, code)
      assert.are.equal("ashlar: test: no check script in '" .. folder .. "' matches 'nothing_like_it'\n", output)
    end)

    it("rejects a malformed golden file before running anything", function()
      script("a.lua", "print('ran') check('x', 1)\n")
      local cases = {
        { '{ "a.lua": { "x": 1 }', "parse error at line 1, column 22" },
        { '[1, 2]', "expected an object keyed by script file, found array" },
        { '{ "a.lua": 1 }', '"a.lua": expected an object keyed by check name, found number' },
        { '{ "a.lua": { "x": null } }', '"a.lua" / "x": expected a number, boolean, string or list of numbers, found null' },
        { '{ "a.lua": { "x": [1, "b"] } }', '"a.lua" / "x": expected a list of numbers, found string in it' },
        { '{ "a.lua": { "x": 1e400 } }', "" },
      }
      for _, case in ipairs(cases) do
        write_file(folder .. "/golden.json", case[1])
        for _, update in ipairs{ "", "--update" } do
          local output, code = ashlar_test(update)
          assert.are.equal(1, code)
          assert.matches("^ashlar: test: " .. escape_pattern(folder .. "/golden.json: malformed golden file: ")
                         .. ".*" .. escape_pattern(case[2]), output)
          assert.is_false(has_line(output, "ran"))
          assert.are.equal(case[1], golden_text())
        end
      end
    end)
  end)

  describe("scripts", function()
    it("run in fresh states, sorted by name, with their folder and its subfolders on package.path", function()
      assert(os.execute("mkdir " .. quote(folder .. "/helpers")))
      write_file(folder .. "/helpers/square.lua", "return function(x) return x * x end")
      script("b.lua", "leaked = true\ncheck('square', require('helpers.square')(3))\n")
      script("a.lua", "check('arg', arg[0]:match('[^/]*$'))\ncheck('models', type(require('ashlar.models').arch))\n")
      script("c.lua", "check('fresh', leaked == nil)\n")
      local output, code = ashlar_test("--update")
      assert.are.equal(0, code, output)
      assert.matches("^a%.lua: 2 checks, [%d.]+ s\n.*\nb%.lua: 1 checks, [%d.]+ s\n.*\nc%.lua: 1 checks", output)
      assert.are.equal('{\n  "a.lua": {\n    "arg": "a.lua",\n    "models": "function"\n  },\n'
                       .. '  "b.lua": {\n    "square": 9\n  },\n  "c.lua": {\n    "fresh": true\n  }\n}\n', golden_text())
    end)

    it("can be picked by parts of their names, leaving the others' golden values alone", function()
      script("arch.lua", "check('x', 1)\n")
      script("dome.lua", "check('y', 2)\n")
      assert.are.equal(0, select(2, ashlar_test("--update")))
      script("dome.lua", "check('y', 3)\n")
      script("wall.lua", "check('z', 4)\n")
      local output, code = run(quote(ashlar_bin) .. " test " .. quote(folder) .. " arc")
      assert.are.equal(0, code, output)
      assert.are.equal("1 passed, 0 failed", last_line(output))
      assert.is_nil(output:find("dome", 1, true))
      output, code = run(quote(ashlar_bin) .. " test --update " .. quote(folder) .. " all")
      assert.are.equal(0, code, output)
      assert.is_true(has_line(output, '  added "z": 4'), output)
      assert.matches('"y": 2', golden_text())
    end)

    it("print what they record when run on their own", function()
      local path = script("alone.lua", [[
check("ratio", 0.5, { reference = 0.5, reference_absolute = 1e-9 })
check("far", 2, { reference = 1, reference_tolerance = 0.1 })
check("name", "arch")
]])
      local output, code = run(quote(ashlar_bin) .. " " .. quote(path))
      assert.are.equal(0, code)
      assert.are.equal('ratio: 0.5  (within its reference 0.5)\n'
                       .. 'far: 2  FAILS its reference 1, got 2: relative difference 1 > reference_tolerance 0.1\n'
                       .. 'name: "arch"\n', output)
    end)
  end)

  describe("time limit, parallel runs and JUnit XML", function()
    -- A passing, a failing and a script that runs until stopped. The limit
    -- leaves the other two (a process each, slower under the sanitizers)
    -- ample time.
    local TIMEOUT = 2

    -- The report without the run times, which vary.
    local function without_times(output)
      return (output:gsub("checks, %d+%.%d%d s\n", "checks, T s\n"))
    end

    it("stop a script at the limit, fail it naming the limit, report alike with -j 2, and write JUnit XML", function()
      script("a_pass.lua", 'print("a runs")\ncheck("one", 1)\n')
      script("b_fail.lua", 'check("two", 2, { reference = 3, reference_tolerance = 1e-9 })\n')
      script("c_slow.lua", 'check("started", true)\nlocal stop = os.clock() + 600\nwhile os.clock() < stop do end\n')
      assert.are.equal(1, select(2, run(quote(ashlar_bin) .. " test --update " .. quote(folder) .. " a_pass b_fail")))
      local slow, junit = folder .. "/c_slow.lua", folder .. "/report.xml"
      local reports = {}
      for _, jobs in ipairs{ "-j 1", "--jobs 2" } do
        local output, code = ashlar_test(jobs .. " --timeout " .. TIMEOUT .. " --junit " .. quote(junit))
        assert.are.equal(1, code, output)
        assert.are.equal("1 passed, 2 failed", last_line(output))
        assert.is_true(has_line(output, "  FAIL " .. slow .. ": stopped at the time limit of 2 s (--timeout)"), output)
        local seconds = tonumber(output:match("\nc_slow%.lua: 0 checks, ([%d.]+) s\n"))
        assert.is_true(seconds >= TIMEOUT and seconds < TIMEOUT + 10, "stopped after " .. tostring(seconds) .. " s")
        reports[#reports + 1] = without_times(output)
        -- Parsed by Python's XML parser: counts, names, the console's failure lines.
        local parsed = run("/usr/bin/python3 -c " .. quote([[
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
suite = root.find("testsuite")
print(root.tag, root.get("tests"), root.get("failures"), suite.get("tests"), suite.get("failures"))
for case in suite.findall("testcase"):
    failure = case.find("failure")
    out = case.find("system-out")
    print(case.get("name"), failure.get("message") if failure is not None else "passed",
          repr(out.text) if out is not None else "")
]]) .. " " .. quote(junit))
        assert.are.equal("testsuites 3 2 3 2\n" ..
          "a_pass.lua passed 'a runs\\n'\n" ..
          "b_fail.lua FAIL " .. folder .. '/b_fail.lua:2: "two": reference 3, got 2: relative difference 0.333 > ' ..
          "reference_tolerance 1e-09 \n" ..
          "c_slow.lua FAIL " .. slow .. ": stopped at the time limit of 2 s (--timeout) \n", parsed)
      end
      assert.are.equal(reports[1], reports[2])
      assert.matches("^a runs\na_pass%.lua: 1 checks, T s\nb_fail%.lua: 1 checks, T s\n  FAIL ", reports[1])
      assert.is_true(has_line(reports[1], "wrote " .. junit), reports[1])
    end)

    it("check their options", function()
      script("a.lua", "check('x', 1)\n")
      for _, case in ipairs{
        { "--timeout -1", "--timeout: '-1' is not a number of seconds >= 0 (0: no limit)" },
        { "-j 0", "-j: '0' is not a number of scripts to run at once from 1 to 1024" },
        { "--jobs many", "--jobs: 'many' is not a number of scripts to run at once from 1 to 1024" },
        { "--junit", "'--junit' needs a value" },
      } do
        local output, code = run(quote(ashlar_bin) .. " test " .. quote(folder) .. " " .. case[1])
        assert.are.equal(1, code, case[1])
        assert.matches("^ashlar: test: " .. escape_pattern(case[2]) .. "\nusage: ashlar test", output)
      end
    end)
  end)

  describe("the host", function()
    it("still runs a script named test after -- or as a path", function()
      write_file(folder .. "/test", "print('the script named test', ...)")
      for _, command in ipairs{ "-- test one", "./test one" } do
        local output, code = run("cd " .. quote(folder) .. " && " .. quote(ashlar_bin) .. " " .. command)
        assert.are.equal(0, code, output)
        assert.are.equal("the script named test\tone\n", output)
      end
    end)

    it("lists the test command in its usage, and test its own", function()
      local output, code = run(quote(ashlar_bin) .. " --help")
      assert.are.equal(0, code)
      local usage = "ashlar test %[%-%-update%] %[%-%-timeout S%] %[%-j N%] %[%-%-junit FILE%] %[folder %[name %.%.%.%]%]\n"
      assert.matches("\n       " .. usage, output)
      output, code = run(quote(ashlar_bin) .. " test --help")
      assert.are.equal(0, code)
      assert.matches("^usage: " .. usage, output)
      for _, option in ipairs{ "%-%-update", "%-%-timeout S", "%-j N, %-%-jobs N", "%-%-junit FILE" } do
        assert.matches("\n  " .. option .. " ", output)
      end
      -- The defaults the help gives are those docs/api.md gives.
      local docs = read_file(support.script_folder(1) .. "/../../docs/api.md")
      local timeout = assert(docs:match("\n| `%-%-timeout S` | (%d+) |"))
      local jobs = assert(docs:match("\n| `%-j N`, `%-%-jobs N` | (%d+) |"))
      assert.matches("%(default " .. timeout .. "; 0: no limit%)", output)
      assert.matches("run N scripts at once %(default " .. jobs .. "%)", output)
    end)
  end)
end)
