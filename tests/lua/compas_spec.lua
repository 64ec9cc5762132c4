-- COMPAS Assembly files through the Lua API: import -> analyse -> export ->
-- import gives the same blocks, supports and interfaces and the same
-- analysis; hand-made files of the three layouts read as the same assembly.
-- (The exported forces' balance is checked in tests/unit/test_compas_assembly.cpp.)
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local DATA = "../data/compas/"  -- specs run in tests/lua

local function same_structure(a, b, tolerance)
  assert.equal(#a, #b)
  for i = 1, #a do
    assert.equal(a:name(i), b:name(i))
    assert.equal(a:is_support(i), b:is_support(i))
    local va, vb = a:block(i):volume(), b:block(i):volume()
    assert.near(va, vb, tolerance * va)
    for k = 1, 3 do assert.near(a:block(i):centroid()[k], b:block(i):centroid()[k], tolerance) end
  end
  local fa, fb = a:interfaces(), b:interfaces()
  assert.equal(#fa, #fb)
  for k = 1, #fa do
    assert.equal(fa[k].a, fb[k].a)
    assert.equal(fa[k].b, fb[k].b)
    assert.near(fa[k].area, fb[k].area, tolerance * fa[k].area)
  end
end

describe("a COMPAS assembly", function()
  local folder
  setup(function() folder = support.temp_folder() end)
  teardown(function() support.remove_folder(folder) end)

  it("comes back from import -> analyse -> export -> import as the same assembly and analysis", function()
    local s = models.dome{ parallels = 8, meridians = 12 }
    local r = ashlar.analyze(s, { friction = 0.6 })
    assert.equal("converged", r.status)
    local first = folder .. "/dome.json"
    ashlar.export(s, first, { result = r })
    local a = ashlar.import(first)
    same_structure(s, a, 1e-12)
    for _, c in ipairs(a:interfaces()) do assert.is_true(c.explicit) end
    local ra = ashlar.analyze(a, { friction = 0.6 })
    assert.equal(r.stable, ra.stable)
    assert.near(r.objective, ra.objective, 1e-9 * math.abs(r.objective))

    -- Second round: what ashlar wrote it reads back as it was.
    local second = folder .. "/dome2.json"
    ashlar.export(a, second, { format = "compas", result = ra })
    local b = ashlar.import(second)
    same_structure(a, b, 1e-12)
    for k, c in ipairs(a:interfaces()) do
      local d = b:interfaces()[k]
      for i = 1, 3 do assert.near(c.normal[i], d.normal[i], 1e-12) end
      assert.equal(#c.vertices, #d.vertices)
    end
    assert.near(ra.objective, ashlar.analyze(b, { friction = 0.6 }).objective, 1e-9 * math.abs(r.objective))

    -- Contacts left to detection: the same interfaces, not explicit.
    local detected = ashlar.import(first, { interfaces = "detect" })
    same_structure(s, detected, 1e-12)
    for _, c in ipairs(detected:interfaces()) do assert.is_false(c.explicit) end
  end)

  it("reads the compas 2, compas 1 and compas_assembly 0.x layouts alike", function()
    for _, file in ipairs{ "stack_compas2.json", "stack_compas1.json", "stack_assembly0.json" } do
      local s = ashlar.import(DATA .. file)
      assert.equal(3, #s)
      assert.same({ true, false, false }, { s:is_support(1), s:is_support(2), s:is_support(3) })
      local found = s:interfaces()
      assert.equal(2, #found)
      assert.near(1.0, found[1].area, 1e-12)
      assert.near(0.45, found[2].area, 1e-12)
      -- Each joint carries the weight above it.
      local r = ashlar.analyze(s, { friction = 0.5 })
      assert.is_true(r.stable)
      local w2, w3 = 9.81 * s:block(2):mass(), 9.81 * s:block(3):mass()
      assert.near(w2 + w3, r.interfaces[1].normal_force, 1e-6 * (w2 + w3))
      assert.near(w3, r.interfaces[2].normal_force, 1e-6 * w3)
      -- The support option adds supports to those the file flags.
      local t = ashlar.import(DATA .. file, { support = function(name) return name == "top" or name == "node 2" end })
      assert.same({ true, false, true }, { t:is_support(1), t:is_support(2), t:is_support(3) })
    end
  end)

  it("names what is wrong with the options", function()
    local s = models.arch{ voussoirs = 6 }
    local path = folder .. "/arch.json"
    support.expect_error({ "format: expected \"compas\"", "got \"obj\"" }, ashlar.export, s, path, { format = "obj" })
    support.expect_error({ "color: does not apply to a COMPAS assembly" }, ashlar.export, s, path, { color = { 1, 0, 0 } })
    support.expect_error({ "the result is of a structure with 10 blocks, this one has 8" }, ashlar.export, s, path,
      { result = ashlar.analyze(models.arch{ voussoirs = 8 }, {}) })
    ashlar.export(s, path)
    support.expect_error({ "interfaces: expected \"file\"", "got \"all\"" }, ashlar.import, path, { interfaces = "all" })
    local obj = folder .. "/arch.obj"
    ashlar.export(s, obj)
    support.expect_error({ "interfaces: applies to COMPAS assembly files (.json) only" }, ashlar.import, obj,
      { interfaces = "file" })
    local other = folder .. "/other.json"
    s:save(other)  -- an ashlar structure file is not a COMPAS assembly
    support.expect_error({ "not a COMPAS Assembly", "got the fields format, version" }, ashlar.import, other)
  end)

  it("names a bad block's vertices and faces by their keys, as its path does", function()
    -- Node 1's top face is face key "1" = vertices 13, 21, 30, 31 (keys);
    -- lifting vertex 30 by 0.2 m warps it, every corner about 0.2 / 4 m off
    -- the best-fit plane (0.0495 m: the plane also tilts).
    local file = assert(io.open(DATA .. "stack_compas2.json"))
    local text = file:read("a")
    file:close()
    local warped, count = text:gsub('("30": {%s*"x": 0.7,%s*"y": 0.5,%s*"z": )1', "%11.2")
    assert.equal(1, count)
    local path = folder .. "/warped.json"
    file = assert(io.open(path, "w"))
    file:write(warped)
    file:close()
    support.expect_error({ path .. ": graph.node.1.block ('node 1'): block 'node 1' is not a valid block: face 1 is "
      .. "not planar: its vertex 13 is 0.0495074 m off the face's plane", "(vertices and faces by their keys in the file)" },
      ashlar.import, path)
  end)
end)
