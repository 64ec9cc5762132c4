-- Warped faces (CAD exports, remeshed and scanned blocks): the planarity
-- option accepts faces whose vertices lie off their best-fit plane by up to
-- a fraction of the face's size. The solid is then bounded by each face's
-- fan of triangles about its centre, whose volume and centroid are checked
-- here against closed forms.
local ashlar = require "ashlar"
local support = require "spec_support"

-- A unit cube whose top corner (1, 1, 1) is raised by h: the top face
-- (0,0,1) (1,0,1) (1,1,1+h) (0,1,1) is warped; the four sides stay planar.
local function warped_cube_obj(h)
  return ([[
o warped
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 %.17g
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
]]):format(1 + h)
end

describe("planarity", function()
  local folder, path
  local h = 0.01
  setup(function()
    folder = support.temp_folder()
    path = folder .. "/warped.obj"
    support.write_file(path, warped_cube_obj(h))
  end)
  teardown(function() support.remove_folder(folder) end)

  it("is needed for a warped face, and the message says how much", function()
    -- The top face's vertices lie h / 4 off its best-fit plane; its size
    -- (bounding-box diagonal) is sqrt(2 + h^2): a planarity of 0.0018. (The
    -- importer numbers faces and vertices after welding.)
    support.expect_error({ "is not planar", "pass planarity", "needs at least 0.0018" },
      ashlar.import, path)
    support.expect_error({ "warped beyond planarity 0.001", "needs planarity 0.0018" },
      ashlar.import, path, { planarity = 0.001 })
  end)

  it("accepts it, with the exact volume and centroid of the solid its centre fans bound", function()
    local b = ashlar.import(path, { planarity = 0.002 }):block(1)
    -- The top is four triangles fanned from its centre (0.5, 0.5, 1 + h/4),
    -- over quarters of the unit square: the volume above z = 1 is h / 4 and
    -- its moment about z = 0 is h / 4 + 11 h^2 / 192
    -- (tests/unit/test_block_validation.cpp derives both).
    -- (OBJ coordinates are single precision: 1 + h is read to 1e-8.)
    local volume = 1 + h / 4
    assert.near(volume, b:volume(), 1e-8)
    assert.near((0.5 + h / 4 + 11 * h * h / 192) / volume, b:centroid()[3], 1e-8)
    assert.near(h / 4, b:warp(), 1e-4 * h)
    assert.equal(0.002, b:planarity())
    assert.is_true(b:is_convex())
  end)

  it("makes a warped quad that a file holds as two triangles one face again, with the canonical surface", function()
    -- The warped top as two triangles, split along either diagonal: the
    -- one through the raised corner (5-7) bounds a wedge of volume h / 3,
    -- the other (6-8) one of h / 6 (only triangle 6 7 8 rises). Merged, the
    -- quad is one face whose surface is its fan about its centre, whichever
    -- diagonal the file took: the volume 1 + h / 4 of the quad given as one
    -- face, so that two files of one block split differently give one solid.
    for _, case in ipairs{ { "f 5 6 7\nf 5 7 8", h / 3 }, { "f 5 6 8\nf 6 7 8", h / 6 } } do
      local triangles = folder .. "/triangles.obj"
      support.write_file(triangles, (warped_cube_obj(h):gsub("f 5 6 7 8", case[1])))
      local exact = ashlar.import(triangles):block(1)  -- triangles are planar: no planarity needed
      assert.equal(7, #exact:faces())
      assert.near(1 + case[2], exact:volume(), 1e-8)
      local merged = ashlar.import(triangles, { planarity = 0.002 }):block(1)
      assert.equal(6, #merged:faces())
      for _, face in ipairs(merged:faces()) do assert.equal(4, #face) end
      local quad = ashlar.import(path, { planarity = 0.002 }):block(1)
      assert.near(quad:volume(), merged:volume(), 1e-14)
      for k = 1, 3 do assert.near(quad:centroid()[k], merged:centroid()[k], 1e-14) end
      -- A planarity below the quad's warp leaves the triangles as they are.
      assert.equal(7, #ashlar.import(triangles, { planarity = 0.001 }):block(1):faces())
    end
  end)

  it("is kept by save and load, and given to load for files without it", function()
    local s = ashlar.import(path, { planarity = 0.002 })
    local saved = folder .. "/warped.json"
    s:save(saved)
    local loaded = ashlar.load(saved)
    assert.equal(0.002, loaded:block(1):planarity())
    assert.equal(s:block(1):volume(), loaded:block(1):volume())
    -- The same file without the blocks' planarity field.
    local text = support.read_file(saved):gsub('%s*"planarity": [^,]*,', "")
    local bare = folder .. "/bare.json"
    support.write_file(bare, text)
    support.expect_error({ "is not planar", "needs at least 0.0018" }, ashlar.load, bare)
    assert.near(1 + h / 4, ashlar.load(bare, { planarity = 0.002 }):block(1):volume(), 1e-8)
  end)

  it("is an option of ashlar.block, and a block keeps it through rigid motions", function()
    local top = 1 + h
    local b = ashlar.block{
      vertices = { {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, top}, {0, 1, 1} },
      faces = { {1, 4, 3, 2}, {5, 6, 7, 8}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 4, 8, 7}, {4, 1, 5, 8} },
      planarity = 0.002 }
    assert.near(1 + h / 4, b:volume(), 1e-12)
    local moved = b:rotated({ 0, 0, 1 }, 0.3):translated{ 5, 0, 0 }
    assert.equal(0.002, moved:planarity())
    assert.near(b:warp(), moved:warp(), 1e-12)
  end)

  it("refuses values out of range, naming them", function()
    support.expect_error({ "planarity", "got -1" }, ashlar.import, path, { planarity = -1 })
    support.expect_error({ "planarity must be a number from 0 to 0.2", "got 0.5" },
      ashlar.import, path, { planarity = 0.5 })
    support.expect_error({ "planarity", "got string" }, ashlar.load, path, { planarity = "a lot" })
  end)
end)
