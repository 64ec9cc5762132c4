-- The sandbox against hostile scripts (tests/sandbox/hostile): each runs
-- under `ashlar --sandbox scripts/name.lua` from a fresh folder that holds a
-- secret beside the script's folder, symlinks out of the allowed folders
-- and the script's output folder, scripts/out. Each must end with the
-- message its `-- expect:` line names (and the exit status of `-- exit:`,
-- default 1), never with a crash, and leave everything outside scripts/out
-- as it was. `-- unless: X` skips a script when `ashlar -v`
-- mentions X (a build that cannot enforce that limit).
local support = require "spec_support"
local ashlar = require "ashlar"

local ASHLAR = assert(os.getenv("ASHLAR_BIN"), "ASHLAR_BIN: the ashlar host to run")
local HOSTILE = support.script_folder(1) .. "/../sandbox/hostile"
local SECRET = "the secret no script may read"
local quote = support.quote

local function header(script, key)
  local values = {}
  for line in io.lines(script) do
    local value = line:match("^%-%- " .. key .. ": (.*)$")
    if value then values[#values + 1] = value end
  end
  return values[1]
end

local function hostile_scripts()
  local names = {}
  local listing = io.popen("ls " .. quote(HOSTILE))
  for name in listing:lines() do
    if name:match("%.lua$") then names[#names + 1] = name end
  end
  listing:close()
  table.sort(names)
  return names
end

-- A listing of every file and link under root except scripts/out, with
-- contents.
local function snapshot(root)
  return support.run("cd " .. quote(root) ..
    " && find . -path ./scripts/out -prune -o -print | sort && cat secret/secret.txt")
end

-- Runs `file` (in scripts/) sandboxed in a fresh folder; returns the
-- output, the exit code and whether everything outside scripts/out stayed.
local function run_sandboxed(file, options)
  local root = support.temp_folder()
  assert(os.execute(table.concat({
    "cd " .. quote(root),
    "mkdir -p scripts/out secret",
    "printf %s " .. quote(SECRET) .. " > secret/secret.txt",
    "ln -s ../secret scripts/escape",
    "ln -s /etc/passwd scripts/passwd",
    "ln -s ../../secret scripts/out/link",
  }, " && ")))
  assert(os.execute("cp " .. quote(file) .. " " .. quote(root .. "/scripts/")))
  local before = snapshot(root)
  local output, code = support.run("cd " .. quote(root) .. " && " .. quote(ASHLAR) .. " --sandbox " ..
    (options or "") .. " scripts/" .. file:match("[^/]+$"))
  local untouched = snapshot(root) == before
  support.remove_folder(root)
  return output, code, untouched
end

-- A script in sub/ with neighbours it reads by relative paths, writing
-- under its own out/ (sub/out, the default write folder).
local function script_with_neighbours()
  local root = support.temp_folder()
  assert(os.execute("mkdir -p " .. quote(root .. "/sub/lib")))
  support.write_file(root .. "/sub/data.txt", "beside the script")
  support.write_file(root .. "/sub/lib/helper.lua", "return { answer = 42 }")
  support.write_file(root .. "/sub/seven.lua", "return 7")
  support.write_file(root .. "/sub/main.lua", [[
local ashlar = require "ashlar"
local models = require "ashlar.models"
local text = assert(io.open("data.txt")):read("a")
local file = assert(io.open("out/note.txt", "w"))
file:write("written")
file:close()
models.arch{ thickness = 1.0, voussoirs = 4 }:save("out/arch.json")
local values = { text, dofile("seven.lua"), assert(loadfile("seven.lua"))(), require("lib.helper").answer,
                 #ashlar.load("out/arch.json") }
print(table.concat(values, ", "))
return table.unpack(values)
]])
  return root
end

describe("ashlar --sandbox", function()
  local scripts = hostile_scripts()
  local build = support.run(quote(ASHLAR) .. " -v")

  it("has a suite of hostile scripts", function()
    assert.is_true(#scripts >= 60, "only " .. #scripts .. " hostile scripts")
  end)

  for _, name in ipairs(scripts) do
    local path = HOSTILE .. "/" .. name
    local unless = header(path, "unless")
    local test = unless and build:find(unless, 1, true) and pending or it
    test("contains " .. name, function()
      local expected = assert(header(path, "expect"), name .. ": no '-- expect:' line")
      local exit = tonumber(header(path, "exit") or "1")
      local output, code, untouched = run_sandboxed(path, header(path, "options"))
      assert(output:find(expected, 1, true), ("%s: '%s' not in:\n%s"):format(name, expected, output))
      assert.are.equal(exit, code, name .. " exit status; output:\n" .. output)
      assert.is_falsy(output:find(SECRET, 1, true), name .. " read the secret")
      assert.is_falsy(output:find("root:x:0:0", 1, true), name .. " read /etc/passwd")
      assert.is_true(untouched, name .. " changed files outside scripts/out")
      assert.is_falsy(io.open("/tmp/ashlar-sandbox-pwned.txt"), name .. " wrote into /tmp")
    end)
  end

  it("refuses a precompiled script", function()
    local folder = support.temp_folder()
    local chunk = folder .. "/precompiled.luac"
    support.write_file(chunk, string.dump(load("os.execute('touch pwned')")))
    local output, code, untouched = run_sandboxed(chunk)
    support.remove_folder(folder)
    assert(output:find("attempt to load a binary chunk (mode is 't')", 1, true), output)
    assert.are.equal(1, code)
    assert.is_true(untouched)
  end)

  it("runs ordinary scripts as the host does, writing under ./out", function()
    local folder = support.temp_folder()
    support.write_file(folder .. "/model.lua", [[
local models = require "ashlar.models"
local ashlar = require "ashlar"
local r = ashlar.analyze(models.arch{ thickness = 1.0, voussoirs = 16 })
local s = models.arch{ thickness = 1.0, voussoirs = 16 }
s:save("out/arch.json")
print(("stable %s, %d blocks back"):format(tostring(r.stable), #ashlar.load("out/arch.json")))
]])
    local output, code = support.run("cd " .. quote(folder) .. " && " .. quote(ASHLAR) .. " --sandbox model.lua")
    local saved = io.open(folder .. "/out/arch.json")
    support.remove_folder(folder)
    assert.are.equal(0, code, output)
    assert(output:find("stable true, 18 blocks back", 1, true), output)
    assert.is_truthy(saved)
    saved:close()
  end)

  it("resolves relative paths from the script's folder, wherever it is run from", function()
    local root = script_with_neighbours()
    local output, code = support.run("cd " .. quote(root) .. " && " .. quote(ASHLAR) .. " --sandbox sub/main.lua")
    local note = support.read_file(root .. "/sub/out/note.txt")
    local saved = io.open(root .. "/sub/out/arch.json")
    local stray = io.open(root .. "/out")
    support.remove_folder(root)
    assert.are.equal(0, code, output)
    assert.are.equal("beside the script, 7, 7, 42, 6\n", output)
    assert.are.equal("written", note)
    assert.is_truthy(saved)
    saved:close()
    assert.is_nil(stray)
  end)

  it("checks its options", function()
    local cases = {
      { "--read /nonexistent-folder", "allowed folder '/nonexistent-folder' is not an existing folder" },
      { "--memory lots", "'--memory': 'lots' is not a size such as 512M or 2G" },
      { "--time -1", "'--time': '-1' is not a number of seconds >= 0" },
      { "--instructions 1.5", "'--instructions': '1.5' is not a whole number >= 0" },
    }
    for _, case in ipairs(cases) do
      local output, code = support.run(quote(ASHLAR) .. " --sandbox " .. case[1] .. " -e 'print(1)'")
      assert.are.equal(1, code, case[1])
      assert(output:find(case[2], 1, true), case[1] .. ": " .. output)
    end
    local output, code = support.run(quote(ASHLAR) .. " --sandbox --memory")
    assert.are.equal(1, code)
    assert(output:find("'--memory' needs argument", 1, true), output)
    output, code = support.run(quote(ASHLAR) .. " --time 1 -e 'print(1)'")
    assert.are.equal(1, code)
    assert(output:find("need --sandbox", 1, true), output)
  end)
end)

describe("ashlar.sandbox", function()
  it("returns what the script returned, with its usage", function()
    local o = ashlar.sandbox{ source = "return 1 + 1, 'two', {}, ...", args = { "x" } }
    assert.are.equal("ok", o.status)
    assert.are.same({ 2, "two", nil, "x" }, o.results)
    assert.is_true(o.memory_peak > 0 and o.instructions >= 0 and o.seconds >= 0)
  end)

  it("reports each limit as a status", function()
    local memory = ashlar.sandbox{ source = "local t = {}\nfor i = 1, 1e9 do t[i] = i end", memory = 16 * 2^20 }
    assert.are.equal("memory", memory.status)
    -- Where it ran out, as Lua gives the place of an error.
    assert.are.equal("(sandbox source):2: sandbox: memory limit of 16 MiB exceeded (the script's Lua heap)",
      memory.message)
    assert.is_true(memory.memory_peak <= 16 * 2^20)
    local time = ashlar.sandbox{ source = "while true do end", time = 0.2 }
    assert.are.equal("time", time.status)
    assert.is_true(time.seconds >= 0.2 and time.seconds < 2, "stopped after " .. time.seconds .. " s")
    local budget = ashlar.sandbox{ source = "while true do pcall(error) end", instructions = 50000 }
    assert.are.equal("instructions", budget.status)
    assert.is_true(budget.instructions >= 50000 and budget.instructions <= 52000)
    local failed = ashlar.sandbox{ source = "error('plain')" }
    assert.are.equal("error", failed.status)
    assert.truthy(failed.message:find("(sandbox source):1: plain", 1, true))
  end)

  it("confines files to the folders given", function()
    local folder = support.temp_folder()
    support.write_file(folder .. "/inside.txt", "inside")
    local o = ashlar.sandbox{ source = "return io.open(...):read('a')", args = { folder .. "/inside.txt" },
      read = { folder } }
    assert.are.same({ "inside" }, o.results)
    -- Refused as stock Lua's io.open refuses: nil, the reason, an errno (EACCES).
    local refused = ashlar.sandbox{ source = "return io.open(..., 'w')", args = { folder .. "/new.txt" },
      read = { folder } }
    assert.are.equal("ok", refused.status)
    assert.is_nil(refused.results[1])
    assert.are.equal("sandbox: writing '" .. folder .. "/new.txt' is not allowed: outside the allowed folders " ..
      "for writing: none", refused.results[2])
    assert.are.equal(13, refused.results[3])
    local written = ashlar.sandbox{ source = "assert(io.open(..., 'w')):write('made') return 1",
      args = { folder .. "/new.txt" }, write = { folder } }
    assert.are.equal("ok", written.status)
    assert.are.equal("made", support.read_file(folder .. "/new.txt"))
    support.remove_folder(folder)
  end)

  it("runs a script file with its folder readable and its arguments", function()
    local folder = support.temp_folder()
    support.write_file(folder .. "/helper.lua", "return { answer = 42 }")
    support.write_file(folder .. "/main.lua", "return require('helper').answer, arg[0], ...")
    local o = ashlar.sandbox{ script = folder .. "/main.lua", args = { "a" } }
    support.remove_folder(folder)
    assert.are.equal("ok", o.status, o.message)
    assert.are.same({ 42, folder .. "/main.lua", "a" }, o.results)
  end)

  it("resolves a script's relative paths from its folder", function()
    local root = script_with_neighbours()
    assert(os.execute("mkdir " .. quote(root .. "/sub/out")))
    local o = ashlar.sandbox{ script = root .. "/sub/main.lua", write = { root .. "/sub/out" } }
    local note = support.read_file(root .. "/sub/out/note.txt")
    support.remove_folder(root)
    assert.are.equal("ok", o.status, o.message)
    assert.are.same({ "beside the script", 7, 7, 42, 6 }, o.results)
    assert.are.equal("written", note)
  end)

  it("checks its options", function()
    support.expect_error({ "give exactly one of script (a file) and source (a chunk)" }, ashlar.sandbox, {})
    support.expect_error({ "memory: expected a whole number of bytes >= 0" }, ashlar.sandbox,
      { source = "", memory = -1 })
    support.expect_error({ "read[1]: expected a string, got table" }, ashlar.sandbox,
      { source = "", read = { {} } })
    support.expect_error({ "unknown option 'timeout' (allowed: args, instructions, memory, read, script, source, time, write)" }, ashlar.sandbox, { source = "", timeout = 1 })
  end)
end)
