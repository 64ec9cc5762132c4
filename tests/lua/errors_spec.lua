-- Bad input raises a Lua error that says where (file:line), what was wrong
-- and what is allowed; nothing crashes.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local expect_error = require("spec_support").expect_error

local cube_vertices = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 },
                        { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 } }
local cube_faces = { { 1, 3, 4, 2 }, { 5, 6, 8, 7 }, { 1, 2, 6, 5 }, { 3, 7, 8, 4 },
                     { 1, 5, 7, 3 }, { 2, 4, 8, 6 } }

local function without(list, index)
  local out = {}
  for i, v in ipairs(list) do if i ~= index then out[#out + 1] = v end end
  return out
end

describe("argument errors", function()
  it("names unknown options and lists the allowed ones", function()
    expect_error({ "bad argument #1 to ", "unknown option 'colour'", "allowed: center, density, name, size" },
      ashlar.box, { size = { 1, 1, 1 }, colour = 1 })
    expect_error({ "unknown option 'tol'", "allowed: angle, min_area, min_width, tolerance" },
      function() ashlar.structure():interfaces{ tol = 1 } end)
    expect_error({ "unknown option 'suport'" },
      function() ashlar.structure():add(ashlar.box{ size = { 1, 1, 1 } }, { suport = true }) end)
  end)

  it("rejects wrong types, shapes, NaN and infinity", function()
    expect_error({ "size: expected a table of 3 numbers", "got a table of length 2" }, ashlar.box, { size = { 1, 2 } })
    expect_error({ "size[2]: expected a finite number, got nan" }, ashlar.box, { size = { 1, 0 / 0, 1 } })
    expect_error({ "center[3]: expected a finite number, got inf" }, ashlar.box, { size = { 1, 1, 1 }, center = { 0, 0, math.huge } })
    expect_error({ "expected an option table, got string" }, ashlar.box, "big")
    expect_error({ "density: expected a number > 0" }, ashlar.box, { size = { 1, 1, 1 }, density = -5 })
    expect_error({ "box size must be three positive" }, ashlar.box, { size = { 1, -1, 1 } })
    expect_error({ "size: required" }, ashlar.box, {})
    expect_error({ "angle: expected a number, got string" },
      function() ashlar.box{ size = { 1, 1, 1 } }:rotated({ 0, 0, 1 }, "ninety") end)
    expect_error({ "rotation axis must not be zero" },
      function() ashlar.box{ size = { 1, 1, 1 } }:rotated({ 0, 0, 0 }, 1) end)
  end)

  it("shows the value a range check refused", function()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, -0.5 } }, { support = true })
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
    expect_error({ "friction: expected a number >= 0 (math.huge: no sliding), got -1" }, ashlar.analyze, s, { friction = -1 })
    expect_error({ "friction: expected a number >= 0 (math.huge: no sliding), got string" }, ashlar.analyze, s,
      { friction = "high" })
  end)

  it("says which block argument is wrong", function()
    local s = ashlar.structure()
    expect_error({ "bad argument #1 to 'add'", "Block expected, got number" }, function() s:add(5) end)
    expect_error({ "bad argument #1 to 'add'", "Structure expected, got Block" }, function()
      local b = ashlar.box{ size = { 1, 1, 1 } }
      s.add(b, b)
    end)
    s:add(ashlar.box{ size = { 1, 1, 1 } }, { name = "a" })
    expect_error({ "index 7 is out of range", "has 1 blocks" }, function() s:block(7) end)
    expect_error({ "no block is named 'b'" }, function() s:add_load{ block = "b", force = { 0, 0, 1 } } end)
    expect_error({ "force: required" }, function() s:add_load{ block = 1 } end)
    expect_error({ "name 'a' is already used" }, function() s:add(ashlar.box{ size = { 1, 1, 1 } }, { name = "a" }) end)
    s:add(ashlar.box{ size = { 1, 1, 1 } }, { support = true, name = "g" })
    expect_error({ "is a support" }, function() s:add_load{ block = "g", force = { 0, 0, 1 } } end)
  end)

  it("explains invalid geometry", function()
    expect_error({ "block 'open' is not a valid block", "open surface" },
      ashlar.block, { vertices = cube_vertices, faces = without(cube_faces, 6), name = "open" })
    local inverted = {}
    for i, f in ipairs(cube_faces) do inverted[i] = { f[4], f[3], f[2], f[1] } end
    expect_error({ "inverted" }, ashlar.block, { vertices = cube_vertices, faces = inverted })
    expect_error({ "faces[2][3]: expected a vertex index" },
      ashlar.block, { vertices = cube_vertices, faces = { { 1, 2, 3 }, { 1, 2, "x" } } })
    expect_error({ "refers to vertex 9" },
      ashlar.block, { vertices = cube_vertices, faces = { { 1, 3, 4, 9 }, table.unpack(cube_faces, 2) } })
    expect_error({ "needs 'vertices' and 'faces'" }, ashlar.block, { vertices = cube_vertices })
    expect_error({ "hull", "coplanar" }, ashlar.hull, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } })
    expect_error({ "lies in the polygon's plane" }, ashlar.prism, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { 1, 1, 0 })
    expect_error({ "equal vertex counts" }, ashlar.loft,
      { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } })
  end)

  it("reports files that cannot be read or written", function()
    expect_error({ "/nonexistent/x.json" }, ashlar.load, "/nonexistent/x.json")
    expect_error({ "/nonexistent/y.obj" }, ashlar.import, "/nonexistent/y.obj")
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 1, 1 } })
    expect_error({ "/nonexistent/dir/s.json" }, function() s:save("/nonexistent/dir/s.json") end)
    expect_error({ ".xyz", "glb" }, ashlar.export, s, os.tmpname() .. ".xyz")
    expect_error({ "color: colour components must lie in [0, 1], got 2 (component 1)" }, ashlar.export, s, "x.glb",
      { color = { 2, 0, 0 } })
    expect_error({ "color: expected a colour {r, g, b} or {r, g, b, a}, got table of 5 values" }, ashlar.export, s,
      "x.glb", { color = { 0, 0, 0, 1, 1 } })
    expect_error({ "color.values: needs one value per block (1), got 2" }, ashlar.export, s, "x.glb",
      { color = { values = { 1, 2 } } })
    expect_error({ "support: expected a name pattern" }, ashlar.import, "x.obj", { support = 3 })
    expect_error({ "bad argument #3 to ", "unknown option 'color.value'" }, ashlar.export, s, "x.glb",
      { color = { value = { 1 } } })
    expect_error({ "bad argument #3 to ", "color.map: expected a string" }, ashlar.export, s, "x.glb",
      { color = { values = { 1 }, map = 5 } })
  end)

  it("rejects bad model options with the generator's name", function()
    expect_error({ "models.wall: unknown option 'lenght'", "allowed:" }, models.wall, { lenght = 3 })
    expect_error({ "models.wall: bond: 'flemish' is not one of running, stack" }, models.wall, { bond = "flemish" })
    expect_error({ "models.wall: length 4.81 is not a whole number of bricks" }, models.wall, { length = 4.81 })
    expect_error({ "models.wall: thickness: must be > 0" }, models.wall, { thickness = 0 })
  end)

  it("reports a closed object instead of using it", function()
    local b = ashlar.box{ size = { 1, 1, 1 } }
    getmetatable(b).__close(b)
    getmetatable(b).__close(b)  -- idempotent
    expect_error({ "attempt to use a closed Block" }, function() return b:volume() end)
  end)
end)

describe("misspelt names", function()
  it("say which name is missing and the nearest there is", function()
    expect_error({ "ashlar has no function 'analyse' (did you mean 'analyze'?)" }, function() return ashlar.analyse end)
    expect_error({ "models has no function 'arc' (did you mean 'arch'?)" }, function() return models.arc end)
    expect_error({ "ashlar has no function 'compare_method' (did you mean 'compare_methods'?)" },
      function() return ashlar.compare_method end)
    expect_error({ "models has no function 'barel_vualt' (did you mean 'barrel_vault'?)" },
      function() return models.barel_vualt end)
    -- Too far from every name: no guess.
    local message = expect_error({ "ashlar has no function 'xyzzy'" }, function() return ashlar.xyzzy end)
    assert.is_nil(message:find("did you mean", 1, true))
    -- Fields that exist, and keys that are not names, read as always.
    assert.equal("function", type(ashlar.analyze))
    assert.is_nil(ashlar[1])
    -- A user's own library can be strict too.
    local mine = ashlar.strict({ span = 1 }, "mine")
    expect_error({ "mine has no function 'spam' (did you mean 'span'?)" }, function() return mine.spam end)
    expect_error({ "bad argument #1 to 'strict' (the table already has a metatable)" },
      function() ashlar.strict(mine, "again") end)
  end)
end)

describe("integer options", function()
  it("name the argument, the option, the range and the value, and refuse what does not fit", function()
    local s = models.arch{ voussoirs = 6 }
    expect_error({ "bad argument #2 to 'analyze' (friction_sides: expected an integer from 3 to 1024, got 2.5)" },
      function() ashlar.analyze(s, { friction_sides = 2.5 }) end)
    -- 2^32 + 4 used to wrap to 4.
    expect_error({ "friction_sides: expected an integer from 3 to 1024, got 4294967300" },
      function() ashlar.analyze(s, { friction_sides = (1 << 32) + 4 }) end)
    expect_error({ "bad argument #2 to 'analyze' (max_iterations: expected an integer from 1 to 2^31 - 1, got 0)" },
      function() ashlar.analyze(s, { max_iterations = 0 }) end)
    expect_error({ "bad argument #2 to 'optimize' (max_iterations: expected an integer from 0 to 2^31 - 1, got 1.5)" },
      function() ashlar.optimize(function() return s end, { params = { a = 1 }, max_iterations = 1.5 }) end)
    expect_error({ "bad argument #2 to 'optimize' (params.a: expected a number, got string)" },
      function() ashlar.optimize(function() return s end, { params = { a = "x" } }) end)
    expect_error({ "bad argument #3 to 'export' (color[2]: expected a number, got string)" },
      function() ashlar.export(s, os.tmpname() .. ".svg", { color = { 0.1, "a", 0.3 } }) end)
    assert.is_true(ashlar.analyze(s, { friction_sides = 4.0 }).stable)  -- a float with an integer value is one
  end)
end)
