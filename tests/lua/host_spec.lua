-- The `ashlar` host program, run as a subprocess: options, `arg`, errors,
-- exit codes, the REPL, and the C module in a stock lua5.4.
local ashlar_bin = assert(os.getenv("ASHLAR_BIN"), "set ASHLAR_BIN to the ashlar binary")
local module_dir = os.getenv("ASHLAR_MODULE_DIR")

local support = require "spec_support"
local quote, write_file = support.quote, support.write_file

-- Runs shell commands with stdout and stderr together, and `input` (if any)
-- on stdin; returns the output and the exit code of the last command.
local function run(commands, input)
  local redirections = " 2>&1"
  local input_path
  if input then
    input_path = os.tmpname()
    write_file(input_path, input)
    redirections = redirections .. " < " .. quote(input_path)
  end
  local pipe = assert(io.popen("{ " .. commands .. "\n}" .. redirections, "r"))
  local output = pipe:read("a")
  local _, _, code = pipe:close()
  if input_path then os.remove(input_path) end
  return output, code
end

local function ashlar(arguments, input)
  return run(quote(ashlar_bin) .. " " .. arguments, input)
end

local function escape_pattern(text)
  return (text:gsub("%p", "%%%0"))
end

describe("the ashlar host", function()
  local folder

  -- Scripts go in a fresh folder per test, so paths in messages are known.
  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  local function script(name, text)
    local path = folder .. "/" .. name
    write_file(path, text)
    return path
  end

  describe("options", function()
    it("prints its version with --version", function()
      local output, code = ashlar("--version")
      assert.are.equal(0, code)
      assert.matches("^ashlar %d+%.%d+%.%d+ %(Lua 5%.4%)[%w %[%]]*\n$", output)
    end)

    it("lists its options with --help", function()
      local output, code = ashlar("--help")
      assert.are.equal(0, code)
      for _, option in ipairs{ "-e", "-i", "-l", "-v", "--version", "--help" } do
        assert.matches("\n  " .. escape_pattern(option) .. " ", output)
      end
    end)

    it("rejects an unknown option with the usage and exit status 1", function()
      local output, code = ashlar("--frobnicate")
      assert.are.equal(1, code)
      assert.matches("unrecognized option '%-%-frobnicate'", output)
      assert.matches("usage: ashlar", output)
    end)

    it("rejects -e without its chunk", function()
      local output, code = ashlar("-e")
      assert.are.equal(1, code)
      assert.matches("'%-e' needs argument", output)
    end)

    it("runs -e chunks in order, then the script", function()
      local path = script("after.lua", "print('script', x)")
      local output, code = ashlar("-e 'x = 1' -e 'x = x + 1 print(x)' " .. quote(path))
      assert.are.equal(0, code)
      assert.are.equal("2\nscript\t2\n", output)
    end)

    it("reports an error in -e with its chunk name", function()
      local output, code = ashlar("-e 'error(\"bad\")'")
      assert.are.equal(1, code)
      assert.matches("^ashlar: %(command line%):1: bad\nstack traceback:", output)
    end)

    it("requires a library into a global with -l", function()
      local output, code = ashlar("-l s=string -e 'print(s.upper(\"ok\"))'")
      assert.are.equal(0, code)
      assert.are.equal("OK\n", output)
    end)
  end)

  describe("scripts", function()
    it("gets arg like lua.c and its arguments in ...", function()
      local path = script("args.lua", [[
        print(select("#", ...), ...)
        for i = -3, #arg do print(i, arg[i]) end
      ]])
      local output, code = ashlar("-e 'x=1' " .. quote(path) .. " one 'two words'")
      assert.are.equal(0, code)
      assert.are.equal(table.concat({
        "2\tone\ttwo words",
        "-3\t" .. ashlar_bin,
        "-2\t-e",
        "-1\tx=1",
        "0\t" .. path,
        "1\tone",
        "2\ttwo words",
      }, "\n") .. "\n", output)
    end)

    it("reads the script from stdin with -", function()
      local output, code = ashlar("- a b", "print(arg[0], ...)")
      assert.are.equal(0, code)
      assert.are.equal("-\ta\tb\n", output)
    end)

    it("runs stdin as a script when it is not a terminal", function()
      local output, code = ashlar("", "print('from stdin')\nerror('late')")
      assert.are.equal(1, code)
      assert.matches("^from stdin\nashlar: stdin:2: late\n", output)
    end)

    it("lets a script require modules beside it, from any working folder", function()
      script("neighbour.lua", "return { answer = 42 }")
      assert(os.execute("mkdir " .. quote(folder .. "/folder_module")))
      script("folder_module/init.lua", "return { name = 'folder module' }")
      local path = script("main.lua", [[
        print(require("neighbour").answer, require("folder_module").name)
      ]])
      local output, code = run("cd / && " .. quote(ashlar_bin) .. " " .. quote(path))
      assert.are.equal(0, code)
      assert.are.equal("42\tfolder module\n", output)
    end)

    it("preloads the ashlar library", function()
      local output, code = ashlar("-e 'print(type(require(\"ashlar\").version))'")
      assert.are.equal(0, code)
      assert.are.equal("string\n", output)
    end)

    it("exits with the status given to os.exit", function()
      local cases = { ["os.exit(3)"] = 3, ["os.exit(true)"] = 0, ["os.exit(false)"] = 1,
                      ["os.exit(0, true)"] = 0, ["local x = 1"] = 0 }
      for chunk, expected in pairs(cases) do
        local _, code = ashlar("-e " .. quote(chunk))
        assert.are.equal(expected, code, chunk)
      end
    end)
  end)

  describe("errors", function()
    it("prints file:line and a traceback, and exits with status 1", function()
      local path = script("broken.lua", [[
local function fail()
  error("boom")
end
fail()
]])
      local output, code = ashlar(quote(path))
      assert.are.equal(1, code)
      assert.matches("^ashlar: " .. escape_pattern(path) .. ":2: boom\n", output)
      assert.matches("stack traceback:", output)
      assert.matches(escape_pattern(path) .. ":4: in main chunk", output)
    end)

    it("names a syntax error's file and line", function()
      local path = script("syntax.lua", "local x =\n\n= 2\n")
      local output, code = ashlar(quote(path))
      assert.are.equal(1, code)
      assert.matches("^ashlar: " .. escape_pattern(path) .. ":3: ", output)
    end)

    it("says when the script cannot be opened", function()
      local output, code = ashlar(quote(folder .. "/missing.lua"))
      assert.are.equal(1, code)
      assert.matches("^ashlar: cannot open .*missing%.lua", output)
    end)

    it("shows error objects through __tostring, or names their type", function()
      local output, code = ashlar([[-e 'error(setmetatable({}, {__tostring = function() return "custom" end}))']])
      assert.are.equal(1, code)
      assert.matches("^ashlar: custom\nstack traceback:", output)

      output, code = ashlar("-e 'error({})'")
      assert.are.equal(1, code)
      assert.matches("^ashlar: %(error object is a table value%)\nstack traceback:", output)
    end)

    it("stops a script on SIGINT with 'interrupted!'", function()
      local ready = folder .. "/ready"
      -- The script signals when it runs, so the interrupt cannot come early;
      -- it stops by itself after 20 s if the interrupt is lost.
      local chunk = ("io.open(%q, 'w'):close() local t = os.clock() while os.clock() - t < 20 do end"):format(ready)
      local output, code = run(table.concat({
        quote(ashlar_bin) .. " -e " .. quote(chunk) .. " & pid=$!",
        "while [ ! -e " .. quote(ready) .. " ]; do sleep 0.05; done",
        "kill -INT $pid",
        "wait $pid",
      }, "\n"))
      assert.are.equal(1, code)
      assert.matches("^ashlar: .*interrupted!\nstack traceback:", output)
    end)

    -- SIGTERM (Slurm's scancel and time limit) during each kind of
    -- computation: it stops at a safe point with "terminated (SIGTERM)", no
    -- verdict, and the process ends by SIGTERM (the shell's 143). The
    -- analysis is big enough (2,500 blocks) that its factorisation is
    -- split over two cores, where METIS once left a handler of its own
    -- for SIGTERM behind, and a SIGTERM crashed the process.
    local function terminate_during(computation)
      local ready = folder .. "/ready_term"
      os.remove(ready)
      -- If the computation ends before the signal, the script says what it
      -- returned and waits (up to 20 s) to be terminated.
      local path = script("terminated.lua", ("local function ready() io.open(%q, 'w'):close() end\n"):format(ready)
        .. computation .. "\nlocal t = os.clock() while os.clock() - t < 20 do end")
      -- Waits for the signal that the computation has begun while the
      -- script still runs (at most 120 s: set-up under the sanitizers).
      local output, code = run(table.concat({
        quote(ashlar_bin) .. " " .. quote(path) .. " & pid=$!",
        "waited=0",
        "while [ ! -e " .. quote(ready) .. " ] && kill -0 $pid 2>/dev/null && [ $waited -lt 2400 ]; do",
        "  sleep 0.05; waited=$((waited + 1))",
        "done",
        "sleep 0.2",
        "kill -TERM $pid",
        "wait $pid",
      }, "\n"))
      assert.are.equal(128 + 15, code, output)
      assert.matches("terminated %(SIGTERM%)", output)
      return output
    end

    it("ends an analysis on SIGTERM, cleanly and with no verdict", function()
      local output = terminate_during([[
        local s = models.wall{ length = 12, height = 3.5 }
        s:set_planar(false)
        ready()
        local r = ashlar.analyze(s)
        print("returned", r.status, r.stable)]])
      -- Stopped inside the solve (the status says so) or at the next Lua
      -- instruction after it; never a verdict.
      assert.is_nil(output:match("returned\t[^\n]*true"), output)
    end)

    it("ends an FEA, a simulation and a study on SIGTERM", function()
      terminate_during([[
        local s = models.arch{ voussoirs = 40 }
        ready()
        print("returned", ashlar.fea(s, { refine = 6 }).status)]])
      terminate_during([[
        local s = models.arch{ voussoirs = 40, thickness = 0.1 }
        ready()
        print("returned", ashlar.simulate(s, { duration = 60 }).status)]])
      -- A study keeps every row it finished; the next run runs only the rest.
      local db = folder .. "/terminated.sqlite"
      -- Terminated once row 10 has started (rows 1-8 or so are done then).
      local study = ("local st = ashlar.study{ name = 'busy', db = %q, params = { a = ashlar.range(1, 60, 60) }, "
        .. "workers = 2, progress = false, run = function(p) if p.a >= 10 and ready then ready() end "
        .. "local t = os.clock() while os.clock() - t < 0.05 do end return { twice = 2 * p.a } end }\n"):format(db)
      terminate_during(study)
      local output, code = ashlar(quote(script("resumed.lua", study .. [[
        local info = st:info()
        local right = 0
        for _, row in ipairs(st:rows()) do if row.twice == 2 * row.a then right = right + 1 end end
        print(info.rows, info.ok, info.errors, info.ran, right)]])))
      assert.are.equal(0, code, output)
      local rows, ok, errors, ran, right = output:match("(%d+)\t(%d+)\t(%d+)\t(%d+)\t(%d+)")
      assert.are.same({ "60", "60", "0", "60" }, { rows, ok, errors, right }, output)
      -- Some rows were kept from the terminated run, so fewer ran again.
      assert.is_true(tonumber(ran) < 60, output)
    end)

    it("stops only the prompt's chunk that Ctrl-C came in: the next analysis runs", function()
      local ready = folder .. "/ready_prompt"
      os.remove(ready)
      local busy = ("io.open(%q, 'w'):close() local t = os.clock() while os.clock() - t < 20 do end"):format(ready)
      local after = "r = ashlar.analyze(models.arch{}) print(r.status, r.stable, " ..
                    "ashlar.load_factor(models.arch{}, {}).status)"
      -- The second line waits in the pipe until the first is interrupted.
      local output, code = run(table.concat({
        "{ printf '%s\\n' " .. quote(busy) .. "; while [ ! -e " .. quote(ready) .. " ]; do sleep 0.05; done;",
        "  printf '%s\\n' " .. quote(after) .. "; } | " .. quote(ashlar_bin) .. " -i & pid=$!",
        "while [ ! -e " .. quote(ready) .. " ]; do sleep 0.05; done",
        "kill -INT $pid",
        "wait $pid",
      }, "\n"))
      assert.are.equal(0, code, output)
      assert.matches("interrupted!\nstack traceback:", output)
      assert.matches("\n> converged\ttrue\toptimal\n", output)
    end)
  end)

  -- glibc's malloc takes transparent huge pages only with the tunable
  -- glibc.malloc.hugetlb=1, which the host adds to GLIBC_TUNABLES by
  -- starting itself again, then puts the user's environment back
  -- (host/host.cpp). Release suite only: under the sanitizers ASan's
  -- allocator replaces glibc's and the host leaves the tunable alone.
  describe("huge pages", function()
    local modes = io.open("/sys/kernel/mm/transparent_hugepage/enabled")
    local offered = modes and modes:read("a") or "[never]"
    if modes then modes:close() end
    -- Where the kernel gives them on request only (not to every process).
    local on_request = offered:find("[madvise]", 1, true) ~= nil
    local given = on_request or offered:find("[always]", 1, true) ~= nil

    -- A host started with GLIBC_TUNABLES as given (nil: not set; this
    -- spec's own host has it set) and `environment` before it: after Lua
    -- has made a 64 MiB string (one block of glibc's malloc), the kB of
    -- huge pages backing the host's memory, then the environment that a
    -- script sees and that a program it runs inherits, and the arguments.
    local function start(tunables, environment)
      local command = (tunables and ("env GLIBC_TUNABLES=" .. quote(tunables)) or "env -u GLIBC_TUNABLES")
        .. " " .. (environment or "") .. " " .. quote(ashlar_bin) .. " - one 'two words'"
      local output, code = run(command, [[
        local block = string.rep("x", 64 << 20)
        local huge
        for line in io.lines("/proc/self/smaps_rollup") do huge = huge or line:match("^AnonHugePages:%s*(%d+) kB") end
        local child = io.popen("echo \"$GLIBC_TUNABLES\" $ASHLAR_GLIBC_TUNABLES_WERE $ASHLAR_GLIBC_TUNABLES_WERE_UNSET")
        print(huge, os.getenv("GLIBC_TUNABLES"), child:read("l"), ...)
        child:close()
      ]])
      assert.are.equal(0, code, output)
      local kb, seen, inherited, arguments = output:match("^(%d+)\t([^\t]*)\t([^\t]*)\t(.*)\n$")
      assert.are.equal("one\ttwo words", arguments, output)
      return tonumber(kb), seen, inherited
    end

    it("backs a large block with huge pages, the user's GLIBC_TUNABLES kept for the script #unsanitized", function()
      if not given then return end
      local kb, seen, inherited = start(nil)
      assert.is_true(kb >= 2048, "huge pages " .. kb .. " kB")  -- at least one 2 MiB page
      assert.are.equal("nil", seen)
      assert.are.equal("", inherited)
      kb, seen, inherited = start("glibc.malloc.arena_max=2")
      assert.is_true(kb >= 2048, "huge pages " .. kb .. " kB")
      assert.are.equal("glibc.malloc.arena_max=2", seen)
      assert.are.equal("glibc.malloc.arena_max=2", inherited)
    end)

    it("keeps the user's own value of the tunable and leaves preloaded allocators alone #unsanitized", function()
      if not on_request then return end
      local kb, seen = start("glibc.malloc.hugetlb=0")
      assert.are.equal(0, kb)
      assert.are.equal("glibc.malloc.hugetlb=0", seen)
      -- As valgrind preloads its own allocator (libm stands in for it).
      kb, seen = start(nil, "LD_PRELOAD=libm.so.6")
      assert.are.equal(0, kb)
      assert.are.equal("nil", seen)
    end)
  end)

  describe("globals", function()
    it("gives -e chunks and the prompt ashlar and models without a require", function()
      local output, code = ashlar("-e " .. quote("print(#ashlar.structure(), #models.arch{ voussoirs = 6 })"))
      assert.are.equal(0, code, output)
      assert.are.equal("0\t8\n", output)
      output, code = ashlar("-i", "#models.stack{}\n")
      assert.are.equal(0, code, output)
      assert.matches("> 6\n", output)
    end)
  end)

  describe("interactive mode", function()
    it("prints values of expressions and continues incomplete statements", function()
      local output, code = ashlar("-i", "1 + 1\nx = 'set'\nx, 2\nfor i = 1, 2 do\nprint('loop', i)\nend\n")
      assert.are.equal(0, code)
      assert.matches("^ashlar %d+%.%d+%.%d+ %(Lua 5%.4%)[%w %[%]]*\n", output)
      assert.matches("> 2\n> > set\t2\n> >> >> loop\t1\nloop\t2\n> \n$", output)
    end)

    it("reports errors and goes on", function()
      local output, code = ashlar("-i", "error('oops')\nprint('after')\n")
      assert.are.equal(0, code)
      assert.matches("stdin:1: oops\nstack traceback:", output)
      assert.matches("after\n", output)
    end)

    it("runs the script first with -i", function()
      local path = script("state.lua", "value = 7")
      local output, code = ashlar("-i " .. quote(path), "value * 6\n")
      assert.are.equal(0, code)
      assert.matches("> 42\n", output)
    end)
  end)

  describe("busted", function()
    it("runs under the host", function()
      assert.is_not_nil(package.preload.ashlar, "this spec should run inside ashlar")
      local passing = script("passing_spec.lua", "it('passes', function() assert.is_true(true) end)")
      local output, code = ashlar("/usr/bin/busted --output=TAP " .. quote(passing))
      assert.are.equal(0, code, output)
      assert.matches("ok 1 %- passes", output)

      local failing = script("failing_spec.lua", "it('fails', function() assert.is_true(false) end)")
      output, code = ashlar("/usr/bin/busted --output=TAP " .. quote(failing))
      assert.are_not.equal(0, code, output)
      assert.matches("not ok 1 %- fails", output)
    end)
  end)

  describe("the C module", function()
    it("loads in a stock lua5.4 and gives the host's version", function()
      assert.is_not_nil(module_dir, "set ASHLAR_MODULE_DIR to the folder of ashlar.so")
      local host_version = ashlar("--version"):match("^ashlar (%S+)")
      local output, code = run("lua5.4 -e " .. quote(("package.cpath = %q .. ';' .. package.cpath"):format(module_dir .. "/?.so"))
        .. " -e " .. quote('local a = require "ashlar" print(a.version)'))
      assert.are.equal(0, code, output)
      assert.are.equal(host_version .. "\n", output)
    end)

    it("loads the model library first, before ashlar itself", function()
      local output, code = run("lua5.4 -e " .. quote(("package.cpath = %q .. ';' .. package.cpath"):format(module_dir .. "/?.so"))
        .. " -e " .. quote('local models = require "ashlar.models" print(#models.arch{ voussoirs = 6 })'))
      assert.are.equal(0, code, output)
      assert.are.equal("8\n", output)
    end)
  end)
end)
