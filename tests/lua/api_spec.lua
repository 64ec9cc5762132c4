-- The public Lua API of the foundation: blocks, structures, contacts, files.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near, tmpdir = support.near, support.temp_folder

local function stack()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true })
  for i = 1, 3 do
    s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.1 * i, 0, 0.25 + 0.5 * (i - 1) } })
  end
  return s
end

describe("ashlar", function()
  it("has a semantic version", function()
    assert.is_truthy(ashlar.version:match("^%d+%.%d+%.%d+$"))
  end)
end)

describe("blocks", function()
  it("box has exact mass properties", function()
    local b = ashlar.box{ size = { 2, 3, 0.5 }, center = { 1, -2, 0.25 }, density = 2000, name = "slab" }
    near(b:volume(), 3, 1e-15)
    near(b:mass(), 6000, 1e-11)
    local c = b:centroid()
    near(c[1], 1, 1e-15); near(c[2], -2, 1e-15); near(c[3], 0.25, 1e-15)
    assert.equal("slab", b:name())
    assert.equal(8, #b:vertices())
    assert.equal(6, #b:faces())
    assert.is_true(b:is_convex())
  end)

  it("block from vertices and 1-based faces round-trips", function()
    local v = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }
    local f = { { 1, 3, 2 }, { 1, 2, 4 }, { 2, 3, 4 }, { 1, 4, 3 } }
    local t = ashlar.block{ vertices = v, faces = f }
    near(t:volume(), 1 / 6, 1e-16)
    assert.same(f, t:faces())
    assert.same(v, t:vertices())
    near(t:mass(), 2400 / 6, 1e-12)
  end)

  it("prism of a non-convex polygon", function()
    local l = { { 0, 0, 0 }, { 3, 0, 0 }, { 3, 1, 0 }, { 1, 1, 0 }, { 1, 3, 0 }, { 0, 3, 0 } }
    local p = ashlar.prism(l, { 0, 0, 2 })
    near(p:volume(), 10, 1e-13)
    assert.is_false(p:is_convex())
    local c = p:centroid()
    near(c[1], 1.1, 1e-14); near(c[3], 1, 1e-14)
  end)

  it("loft makes a frustum", function()
    local bottom = { { -1, -1, 0 }, { 1, -1, 0 }, { 1, 1, 0 }, { -1, 1, 0 } }
    local top = { { -0.5, -0.5, 3 }, { 0.5, -0.5, 3 }, { 0.5, 0.5, 3 }, { -0.5, 0.5, 3 } }
    near(ashlar.loft(bottom, top):volume(), 7, 1e-13)
  end)

  it("hull of the corners of a box has six faces", function()
    local pts = {}
    for x = 0, 1 do for y = 0, 1 do for z = 0, 1 do pts[#pts + 1] = { 2 * x, 3 * y, z } end end end
    pts[#pts + 1] = { 1, 1.5, 0.5 }  -- interior point, not a vertex
    local h = ashlar.hull(pts)
    assert.equal(6, #h:faces())
    near(h:volume(), 6, 1e-14)
  end)

  it("rigid motions keep volume and move the centroid", function()
    local b = ashlar.box{ size = { 1, 2, 3 } }
    local r = b:rotated({ 0, 0, 1 }, math.pi / 2, { 1, 0, 0 }):translated({ 0, 0, 5 })
    near(r:volume(), 6, 1e-14)
    local c = r:centroid()
    near(c[1], 1, 1e-14); near(c[2], -1, 1e-14); near(c[3], 5, 1e-14)
    assert.equal(6, b:volume())  -- the original is unchanged
  end)

  it("split keeps the volume", function()
    local b = ashlar.box{ size = { 2, 2, 2 } }
    local below, above = b:split({ 0.2, 0, 0 }, { 1, 1, 0.5 })
    near(below:volume() + above:volume(), 8, 1e-12)
    assert.is_true(below:centroid()[1] < above:centroid()[1])
    local whole, none = b:split({ 0, 0, 5 }, { 0, 0, 1 })
    near(whole:volume(), 8, 1e-14)
    assert.is_nil(none)
  end)

  it("with renames and changes density", function()
    local b = ashlar.box{ size = { 1, 1, 1 } }:with{ name = "cube", density = 1000 }
    assert.equal("cube", b:name())
    near(b:mass(), 1000, 1e-12)
    assert.is_truthy(tostring(b):match("Block 'cube'"))
  end)
end)

describe("structures", function()
  it("counts blocks and supports, names them", function()
    local s = stack()
    assert.equal(4, #s)
    assert.is_true(s:is_support(1))
    assert.is_false(s:is_support(2))
    assert.equal("block 1", s:name(1))
    assert.equal(2, s:find("block 2"))
    near(s:block(2):volume(), 0.5, 1e-15)
    assert.is_truthy(tostring(s):match("4 blocks, 1 supports"))
  end)

  it("finds the stack's three interfaces exactly", function()
    local found = stack():interfaces()
    assert.equal(3, #found)
    local areas = { 1.0, 0.9, 0.9 }
    for k, f in ipairs(found) do
      assert.equal(k, f.a)
      assert.equal(k + 1, f.b)
      near(f.area, areas[k], 1e-14)
      assert.equal(4, #f.vertices)
      near(f.normal[3], 1, 1e-15)
      near(f.center[3], 0.5 * (k - 1), 1e-14)
    end
  end)

  it("finds the 575 interfaces of a 20 x 10 running-bond wall", function()
    local w = models.wall{ length = 4.8, height = 0.7, brick = { 0.24, 0.07 }, thickness = 0.11 }
    assert.equal(1 + 5 * 20 + 5 * 21, #w)
    local found = w:interfaces()
    assert.equal(5 * 19 + 5 * 20 + 9 * 40 + 20, #found)
    local total = 0
    for _, f in ipairs(found) do total = total + f.area end
    near(total, 195 * 0.07 * 0.11 + 360 * 0.12 * 0.11 + 20 * 0.24 * 0.11, 1e-12)
  end)

  it("takes loads by index or name, defaulting to the centroid", function()
    local s = stack()
    s:add_load{ block = 4, force = { 100, 0, 0 } }
    s:add_load{ block = "block 2", force = { 0, 0, -10 }, at = { 0, 0, 0.5 } }
    local loads = s:loads()
    assert.equal(2, #loads)
    assert.equal(4, loads[1].block)
    near(loads[1].at[3], 1.25, 1e-15)
    assert.equal(2, loads[2].block)
  end)

  it("keeps the planar flag through save and load", function()
    local dir = tmpdir()
    local arch = models.arch{ voussoirs = 8 }
    assert.is_true(arch:is_planar())
    arch:save(dir .. "/arch.json")
    assert.is_true(ashlar.load(dir .. "/arch.json"):is_planar())
    local s = stack()
    assert.is_false(s:is_planar())
    s:save(dir .. "/s.json")
    assert.is_false(ashlar.load(dir .. "/s.json"):is_planar())
    support.remove_folder(dir)
  end)

  it("analyses a planar structure with in-plane equations and the same answer", function()
    local arch = models.arch{ thickness = 0.55, voussoirs = 24 }
    local planar = ashlar.analyze(arch, { friction = math.huge })
    arch:set_planar(false)
    local spatial = ashlar.analyze(arch, { friction = math.huge })
    assert.equal(spatial.stable, planar.stable)
    near(planar.objective, spatial.objective, 1e-6 * math.abs(spatial.objective))
    local s = stack()
    s:set_planar(true)
    s:add_load{ block = 2, force = { 0, 10, 0 } }
    local ok, message = pcall(ashlar.analyze, s)
    assert.is_false(ok)
    assert.is_truthy(message:find("out of the x-z plane", 1, true))
  end)

  it("saves and loads exactly", function()
    local dir = tmpdir()
    local s = stack()
    s:add(ashlar.box{ size = { 0.1, 0.2, 0.3 }, center = { 1 / 3, math.pi, 1e-7 }, density = 1234.5 },
      { name = "odd" })
    s:add_load{ block = "odd", force = { 1 / 7, 0, -2 } }
    s:save(dir .. "/s.json")
    local t = ashlar.load(dir .. "/s.json")
    assert.equal(#s, #t)
    for i = 1, #s do
      assert.same(s:block(i):vertices(), t:block(i):vertices())
      assert.same(s:block(i):faces(), t:block(i):faces())
      assert.equal(s:name(i), t:name(i))
      assert.equal(s:is_support(i), t:is_support(i))
      assert.equal(s:block(i):density(), t:block(i):density())
    end
    assert.same(s:loads(), t:loads())
    support.remove_folder(dir)
  end)

  it("exports glTF and OBJ, and imports them back block by block", function()
    local dir = tmpdir()
    local s = stack()
    for _, ext in ipairs{ "glb", "gltf", "obj" } do
      local path = dir .. "/stack." .. ext
      ashlar.export(s, path, { color = { 0.1, 0.5, 0.9 } })
      local t = ashlar.import(path, { support = "^block 1$" })
      assert.equal(4, #t, ext)
      assert.is_true(t:is_support(1))
      assert.equal("block 3", t:name(3))
      local volume = 0
      for i = 1, #t do volume = volume + t:block(i):volume() end
      near(volume, 0.4 + 1.5, 1e-6)  -- mesh files store float32 coordinates
      assert.equal(3, #t:interfaces(), ext)
    end
    support.remove_folder(dir)
  end)

  it("exports PLY and STL, which hold one mesh, and imports a single solid back", function()
    local dir = tmpdir()
    local s = ashlar.structure()
    s:add(ashlar.prism({ { 0, 0, 0 }, { 3, 0, 0 }, { 3, 1, 0 }, { 1, 1, 0 }, { 1, 3, 0 }, { 0, 3, 0 } }, { 0, 0, 2 }))
    for _, ext in ipairs{ "ply", "stl" } do
      local path = dir .. "/l." .. ext
      ashlar.export(s, path)
      local t = ashlar.import(path)
      assert.equal(1, #t, ext)
      near(t:block(1):volume(), 10, 1e-5)
      assert.equal(8, #t:block(1):faces(), ext)  -- triangles merged back into polygons
    end
    support.remove_folder(dir)
  end)

  it("chooses supports on import with a function", function()
    local dir = tmpdir()
    ashlar.export(stack(), dir .. "/s.glb", { interfaces = false })
    local t = ashlar.import(dir .. "/s.glb", {
      support = function(name, block) return block:centroid()[3] < 0 end,
    })
    local supports = 0
    for i = 1, #t do if t:is_support(i) then supports = supports + 1 end end
    assert.equal(1, supports)
    support.remove_folder(dir)
  end)

  it("colours blocks from values and a colour map", function()
    local dir = tmpdir()
    local s = stack()
    ashlar.export(s, dir .. "/v.glb", { color = { values = { 1, 2, 3, 4 }, map = "viridis" }, interfaces = true })
    local f = assert(io.open(dir .. "/v.glb", "rb"))
    assert.equal("glTF", f:read(4))
    f:close()
    support.remove_folder(dir)
  end)
end)

describe("utilities", function()
  it("clock is monotonic and memory is reported", function()
    local t0 = ashlar.clock()
    assert.is_true(ashlar.clock() >= t0)
    local m = ashlar.memory()
    assert.is_true(m.resident_mb > 0 and m.peak_mb >= m.resident_mb * 0.5)
  end)
end)

describe("colours", function()
  it("take an opacity as a fourth component", function()
    local dir = tmpdir()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 2, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
    ashlar.export(s, dir .. "/c.obj", { color = { { 0.5, 0.5, 0.5 }, { 0.1, 0.5, 0.9, 0.3 } } })
    local mtl = assert(io.open(dir .. "/c.mtl")):read("a")
    local dissolves = {}
    for d in mtl:gmatch("\nd ([%d.]+)") do dissolves[#dissolves + 1] = tonumber(d) end
    table.sort(dissolves)
    assert.equal(2, #dissolves)
    assert.near(0.3, dissolves[1], 1e-6)  -- the translucent block
    assert.near(1.0, dissolves[2], 1e-6)  -- the opaque one
    ashlar.export(s, dir .. "/c.gltf", { color = { 0.1, 0.5, 0.9, 0.3 } })
    local gltf = assert(io.open(dir .. "/c.gltf")):read("a")
    assert.truthy(gltf:find('"BLEND"', 1, true))
  end)

  it("export draws block edges as one node of thin tubes", function()
    local dir = tmpdir()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 2, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
    ashlar.export(s, dir .. "/e.gltf", { edges = true })
    local gltf = assert(io.open(dir .. "/e.gltf")):read("a")
    assert.truthy(gltf:find('"edges"', 1, true))
    ashlar.export(s, dir .. "/plain.gltf")
    assert.falsy(assert(io.open(dir .. "/plain.gltf")):read("a"):find('"edges"', 1, true))
  end)
end)

describe("export of an analysis", function()
  it("exports forces and a thrust line", function()
    local dir = tmpdir()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 4, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true, name = "ground" })
    s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.25 } }, { name = "base" })
    s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.3, 0, 0.75 } }, { name = "overhang" })
    local r = ashlar.analyze(s, { friction = math.huge })
    assert.is_true(r.stable)
    for _, ext in ipairs{ "glb", "gltf", "obj", "ply", "stl" } do
      ashlar.export(s, dir .. "/a." .. ext, { result = r, forces = true, thrust = true })
    end
    local f = assert(io.open(dir .. "/a.gltf"))
    local gltf = f:read("a")
    f:close()
    for _, node in ipairs{ "force 1-2", "force 2-3", "thrust line" } do
      assert.is_truthy(gltf:find('"' .. node .. '"', 1, true), node)
    end
    assert.is_falsy(gltf:find('"force 1-3"', 1, true))

    local function export_error(options)
      local ok, message = pcall(ashlar.export, s, dir .. "/bad.glb", options)
      assert.is_false(ok)
      return message
    end
    assert.is_truthy(export_error{ forces = true }:find("needs the result", 1, true))
    assert.is_truthy(export_error{ result = s, thrust = true }:find("result: expected a Result", 1, true))
    assert.is_truthy(export_error{ result = r, forces = "yes" }:find("forces: 'yes' is not one of", 1, true))
    local unknown = export_error{ result = r, force = true }
    assert.is_truthy(unknown:find("unknown option", 1, true) and unknown:find("forces", 1, true))
    s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 1.25 } })
    assert.is_truthy(export_error{ result = r, forces = true }:find("3 blocks, this one has 4", 1, true))
    support.remove_folder(dir)
  end)
end)
