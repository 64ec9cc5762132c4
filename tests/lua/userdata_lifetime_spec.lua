-- Lifetime of every userdata type: __close and __gc release the C++ object
-- once however often they run, a closed object says so when used, objects
-- made from a closed one stay usable, a binding finishes with an object
-- that Lua code closes under it, and making and dropping objects leaves the
-- Lua heap as it was. Under the sanitizer build ASan catches a double
-- release or a use after free, and LeakSanitizer a leak at exit.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local expect_error = support.expect_error

-- One maker per public userdata type, named as its metatable is.
local makers = {
  ["ashlar.Block"] = function() return ashlar.box{ size = { 1, 1, 1 } } end,
  ["ashlar.Structure"] = function() return models.stack{} end,
  ["ashlar.Result"] = function() return ashlar.analyze(models.stack{}) end,
  ["ashlar.FeaResult"] = function() return ashlar.fea(models.stack{}) end,
  ["ashlar.Simulation"] = function() return ashlar.simulate(models.stack{}, { duration = 0.01 }) end,
  ["ashlar.GroundMotion"] = function() return ashlar.ground_motion{ path = "../data/ground_motion/triangle.at2" } end,
  ["ashlar.Study"] = function()
    return ashlar.study{ name = "lifetime", params = { x = { 1, 2 } }, workers = 1, progress = false,
                         run = function(p) return { y = 2 * p.x } end }
  end,
}
-- Kept in the registry for study workers, never handed to scripts; checked
-- in a host of its own below.
local internal = { ["ashlar.ScriptInvocation"] = true }

local function short_name(metatable) return (metatable:gsub("^ashlar%.", "")) end

local function close(object) getmetatable(object).__close(object) end
local function collect(object) getmetatable(object).__gc(object) end

-- Every way of using an object through its metatable: each method, a field
-- read for types whose __index is a function, and #.
local function uses(object)
  local metatable = getmetatable(object)
  local list = {}
  if type(metatable.__index) == "table" then
    for name, method in pairs(metatable.__index) do
      list[#list + 1] = { name, function() return method(object) end }
    end
  else
    list[#list + 1] = { "a field", function() return object.anything end }
  end
  if metatable.__len then list[#list + 1] = { "#", function() return #object end } end
  return list
end

describe("userdata types", function()
  it("are all covered by this spec", function()
    local found = {}
    for key, value in pairs(debug.getregistry()) do
      if type(key) == "string" and key:match("^ashlar%.") and type(value) == "table"
          and value.__name == key and not internal[key] then
        found[#found + 1] = key
      end
    end
    table.sort(found)
    assert.same(support.sorted_keys(makers), found)
  end)

  for metatable, make in pairs(makers) do
    local type_name = short_name(metatable)
    describe(type_name, function()
      it("has __gc and __close", function()
        local object = make()
        assert.equal("function", type(getmetatable(object).__gc))
        assert.equal("function", type(getmetatable(object).__close))
      end)

      it("closes twice, then is collected", function()
        local object = make()
        close(object)
        close(object)
        collect(object)
        object = nil
        collectgarbage()
        collectgarbage()
      end)

      it("is closed by a <close> variable, and again by hand", function()
        local kept
        do
          local object <close> = make()
          kept = object
        end
        expect_error({ "attempt to use a closed " .. type_name }, function() return uses(kept)[1][2]() end)
        close(kept)
      end)

      it("names its type and says it was closed when used after close", function()
        local object = make()
        local list = uses(object)
        assert.is_true(#list > 0)
        close(object)
        for _, use in ipairs(list) do
          local message = expect_error({ "attempt to use a closed " .. type_name }, use[2])
          assert.is_nil(message:find("attempt to index", 1, true), use[1] .. ": " .. message)
        end
        assert.equal(type_name .. " (closed)", tostring(object))
      end)
    end)
  end
end)

describe("a closed object as an argument", function()
  it("is reported by the function it is passed to", function()
    local block, structure = makers["ashlar.Block"](), makers["ashlar.Structure"]()
    close(block)
    expect_error({ "attempt to use a closed Block" }, function() structure:add(block) end)
    close(structure)
    expect_error({ "bad argument #1 to 'analyze'", "attempt to use a closed Structure" },
                 function() ashlar.analyze(structure) end)
    local result = makers["ashlar.Result"]()
    close(result)
    expect_error({ "bad argument #2 to 'analyze'", "warm_start: attempt to use a closed Result" },
                 function() ashlar.analyze(models.stack{}, { warm_start = result }) end)
  end)
end)

describe("objects made from a closed one", function()
  it("stay usable", function()
    local s = models.stack{}
    local block = s:block(1)
    local r = ashlar.analyze(s)
    local fe = ashlar.fea(s)
    close(s)
    assert.is_true(block:volume() > 0)
    assert.is_boolean(r.stable)
    assert.is_true(#fe.displacements > 0)
  end)
end)

-- Lua code that a binding runs while it works on an object (a callback, an
-- option table's __index) may close that object: the binding finishes with
-- the object it was given, and only later uses see it closed.
-- Lua code that a binding runs while it works on an object (a callback, an
-- option table's __index) may close that object: the binding finishes with
-- the object it was given, and only later uses see it closed.
describe("an object closed while a binding uses it", function()
  -- An option table that closes `object` when the binding reads `key`.
  local function closing_on(key, object, options)
    return setmetatable(options or {}, { __index = function(_, read)
      if read == key then close(object) end
    end })
  end

  it("is a Structure being analysed or optimised", function()
    local s = models.stack{}
    assert.is_boolean(ashlar.analyze(s, closing_on("friction", s)).stable)
    expect_error({ "attempt to use a closed Structure" }, function() return #s end)
    s = models.stack{}
    local optimized = ashlar.optimize(s, { max_iterations = 1, progress = false,
      fixed_vertices = function() close(s) return false end })
    assert.equal(#models.stack{}, #optimized.structure)
  end)

  it("is a Result being exported or drawn", function()
    local folder = support.temp_folder()
    local s = models.stack{}
    for _, writer in ipairs{ { ashlar.export, "stack.glb" }, { ashlar.draw, "stack.svg" } } do
      local r = ashlar.analyze(s)
      writer[1](s, folder .. "/" .. writer[2], closing_on("forces", r, { result = r }))
      expect_error({ "attempt to use a closed Result" }, function() return r.stable end)
    end
    support.remove_folder(folder)
  end)
end)

describe("the host's script record", function()
  it("is destroyed once however often its __gc runs", function()
    local folder = support.temp_folder()
    local script = folder .. "/gc_twice.lua"
    support.write_file(script, [[
      local invocation = debug.getregistry()["ashlar.script"]
      local gc = getmetatable(invocation).__gc
      gc(invocation)
      gc(invocation)
      collectgarbage()
      print("done")
    ]])
    local output, code = support.run(support.quote(assert(os.getenv("ASHLAR_BIN"))) .. " " .. support.quote(script))
    support.remove_folder(folder)
    assert.equal(0, code, output)
    assert.equal("done\n", output)
  end)
end)

-- Lua's own heap must come back to where it was (an object kept alive by a
-- forgotten reference costs it at least 60 bytes: 100 of them, 6 KiB); the
-- C++ objects are LeakSanitizer's to check, at exit in the sanitizer build.
describe("making and dropping 100 objects", function()
  for metatable, make in pairs(makers) do
    it("of type " .. short_name(metatable) .. " leaves the Lua heap as it was", function()
      local function churn(count)
        for round = 1, count do
          local object = make()
          if round % 2 == 0 then close(object) end
        end
        collectgarbage()
        collectgarbage()
      end
      churn(10)
      local before_kib = collectgarbage("count")
      churn(100)
      local growth_kib = collectgarbage("count") - before_kib
      assert.is_true(growth_kib < 2, ("the Lua heap grew by %.1f KiB"):format(growth_kib))
    end)
  end
end)
