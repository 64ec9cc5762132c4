-- The catalogue of bad geometry (docs/api.md, "Bad geometry: what is
-- refused and what is reported"). Every bad input goes in through each door
-- a user has: ashlar.block and the other constructors, ashlar.import of
-- OBJ, OFF, PLY and STL files, ashlar.load of structure files, and the
-- analyses of a structure. Each gives an error that names the object and
-- says what was expected, or a documented status in the result.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local expect_error = support.expect_error

------------------------------------------------------------------------
-- Solids: vertex lists and 1-based faces, counter-clockwise from outside
------------------------------------------------------------------------

local function copy(t)
  local out = {}
  for k, v in pairs(t) do out[k] = type(v) == "table" and copy(v) or v end
  return out
end

local function reversed(face)
  local out = {}
  for i = #face, 1, -1 do out[#out + 1] = face[i] end
  return out
end

local function scaled(vertices, factor, offset)
  local out = {}
  for i, p in ipairs(vertices) do
    out[i] = { p[1] * factor + (offset or 0), p[2] * factor, p[3] * factor }
  end
  return out
end

local CUBE_VERTICES = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 },
                        { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 }, { 1, 1, 1 } }
local CUBE_FACES = { { 1, 3, 4, 2 }, { 5, 6, 8, 7 }, { 1, 2, 6, 5 }, { 3, 7, 8, 4 },
                     { 1, 5, 7, 3 }, { 2, 4, 8, 6 } }

local function cube() return { vertices = copy(CUBE_VERTICES), faces = copy(CUBE_FACES) } end

local solids = {}

solids.open = cube()
table.remove(solids.open.faces, 1)

solids.inverted = cube()
for i, face in ipairs(solids.inverted.faces) do solids.inverted.faces[i] = reversed(face) end

solids.one_face_flipped = cube()
solids.one_face_flipped.faces[2] = reversed(solids.one_face_flipped.faces[2])

-- A tetrahedron whose apex lies in its base's plane, inside the base: every
-- face has area, but the solid is flat.
solids.flat = { vertices = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0.25, 0.25, 0 } },
                faces = { { 1, 3, 2 }, { 1, 2, 4 }, { 2, 3, 4 }, { 3, 1, 4 } } }

-- Vertex 9 repeats vertex 8's point; the top and a side use one each.
solids.coincident = cube()
solids.coincident.vertices[9] = { 1, 1, 1 }
solids.coincident.faces[6] = { 2, 4, 9, 6 }

solids.repeated_corner = cube()
solids.repeated_corner.faces[1] = { 1, 3, 4, 4, 2 }

-- Face 3 is the triangle (1, 2, 9) with vertex 9 on the edge from 1 to 2:
-- no area. The front face runs through 9 so that the surface is closed.
solids.zero_area_face = cube()
solids.zero_area_face.vertices[9] = { 0.5, 0, 0 }
solids.zero_area_face.faces[3] = { 1, 9, 2, 6, 5 }
table.insert(solids.zero_area_face.faces, 3, { 1, 2, 9 })

solids.non_planar = cube()
solids.non_planar.vertices[8] = { 1, 1, 1.2 }

-- A cube whose top is a tent pushed down through the bottom: one closed,
-- outward surface (volume 1/2) whose tent triangles cross the bottom face.
solids.self_intersecting = cube()
solids.self_intersecting.vertices[9] = { 0.5, 0.5, -0.5 }
solids.self_intersecting.faces[2] = { 5, 6, 9 }
for _, face in ipairs{ { 6, 8, 9 }, { 8, 7, 9 }, { 7, 5, 9 } } do
  table.insert(solids.self_intersecting.faces, face)
end

-- Two cubes, one inside the other's corner, as one block: two solids that
-- would move as one rigid body.
solids.two_pieces = cube()
for i = 1, 8 do
  local p = CUBE_VERTICES[i]
  solids.two_pieces.vertices[8 + i] = { p[1] + 0.5, p[2] + 0.5, p[3] + 0.5 }
end
for i = 1, 6 do
  local face = {}
  for k, index in ipairs(CUBE_FACES[i]) do face[k] = index + 8 end
  solids.two_pieces.faces[6 + i] = face
end

-- Two cubes that share only the edge from vertex 4 to vertex 8, as one
-- block: four faces meet at that edge.
solids.non_manifold = cube()
do
  local shared = { [1] = 4, [5] = 8 }  -- the second cube's corners on the first's
  local index = {}
  for i, p in ipairs(CUBE_VERTICES) do
    if shared[i] then
      index[i] = shared[i]
    else
      table.insert(solids.non_manifold.vertices, { p[1] + 1, p[2] + 1, p[3] })
      index[i] = #solids.non_manifold.vertices
    end
  end
  for _, face in ipairs(CUBE_FACES) do
    local moved = {}
    for k, i in ipairs(face) do moved[k] = index[i] end
    table.insert(solids.non_manifold.faces, moved)
  end
end

-- A prism over the bow tie (0, 0), (3, 1), (3, 0), (0, 2), whose lobes
-- have unequal areas: closed and oriented, but its caps cross themselves.
solids.crossed_outline = {
  vertices = { { 0, 0, 0 }, { 3, 1, 0 }, { 3, 0, 0 }, { 0, 2, 0 }, { 0, 0, 1 }, { 3, 1, 1 }, { 3, 0, 1 }, { 0, 2, 1 } },
  faces = { { 4, 3, 2, 1 }, { 5, 6, 7, 8 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 4, 8, 7 }, { 4, 1, 5, 8 } } }

solids.nan = cube()
solids.nan.vertices[3] = { 0 / 0, 1, 0 }
solids.inf = cube()
solids.inf.vertices[3] = { math.huge, 1, 0 }
solids.minus_inf = cube()
solids.minus_inf.vertices[3] = { 0, -math.huge, 0 }

solids.tiny = { vertices = scaled(CUBE_VERTICES, 1e-9), faces = copy(CUBE_FACES) }
solids.huge = { vertices = scaled(CUBE_VERTICES, 1e9), faces = copy(CUBE_FACES) }
solids.too_small = { vertices = scaled(CUBE_VERTICES, 1e-200), faces = copy(CUBE_FACES) }
solids.too_large = { vertices = scaled(CUBE_VERTICES, 1e200), faces = copy(CUBE_FACES) }
solids.far_away = { vertices = scaled(CUBE_VERTICES, 1, 1e9), faces = copy(CUBE_FACES) }

------------------------------------------------------------------------
-- Files holding one solid
------------------------------------------------------------------------

local folder = support.temp_folder()

local function lines_to(path, lines)
  support.write_file(path, table.concat(lines, "\n") .. "\n")
  return path
end

local function number_text(x) return ("%.17g"):format(x) end

local writers = {}

function writers.obj(path, solid)
  local lines = { "o keystone" }
  for _, p in ipairs(solid.vertices) do
    lines[#lines + 1] = ("v %s %s %s"):format(number_text(p[1]), number_text(p[2]), number_text(p[3]))
  end
  for _, face in ipairs(solid.faces) do lines[#lines + 1] = "f " .. table.concat(face, " ") end
  return lines_to(path, lines)
end

local function zero_based(face)
  local out = {}
  for k, index in ipairs(face) do out[k] = index - 1 end
  return table.concat(out, " ")
end

-- OFF and PLY (ASCII) list "x y z" per vertex, then "n i j k ..." per
-- face (0-based) after their headers.
local function counted_lines(path, header, solid)
  local lines = header
  for _, p in ipairs(solid.vertices) do
    lines[#lines + 1] = ("%s %s %s"):format(number_text(p[1]), number_text(p[2]), number_text(p[3]))
  end
  for _, face in ipairs(solid.faces) do lines[#lines + 1] = #face .. " " .. zero_based(face) end
  return lines_to(path, lines)
end

function writers.off(path, solid)
  return counted_lines(path, { "OFF", ("%d %d 0"):format(#solid.vertices, #solid.faces) }, solid)
end

function writers.ply(path, solid)
  return counted_lines(path, { "ply", "format ascii 1.0", "element vertex " .. #solid.vertices,
                               "property float x", "property float y", "property float z",
                               "element face " .. #solid.faces, "property list uchar int vertex_indices",
                               "end_header" }, solid)
end

-- Binary STL: little-endian float32 triangles (each face fanned from its
-- first corner), which carry NaN and infinity as they are.
function writers.stl(path, solid)
  local triangles = {}
  for _, face in ipairs(solid.faces) do
    for k = 2, #face - 1 do triangles[#triangles + 1] = { face[1], face[k], face[k + 1] } end
  end
  local parts = { ("keystone"):rep(10):sub(1, 80), string.pack("<I4", #triangles) }
  for _, t in ipairs(triangles) do
    parts[#parts + 1] = string.pack("<fff", 0, 0, 0)
    for _, index in ipairs(t) do
      local p = solid.vertices[index]
      parts[#parts + 1] = string.pack("<fff", p[1], p[2], p[3])
    end
    parts[#parts + 1] = string.pack("<I2", 0)
  end
  local file = assert(io.open(path, "wb"))
  file:write(table.concat(parts))
  file:close()
  return path
end

-- A structure file as Python's json module writes one: NaN and Infinity bare.
local function json_number(x)
  if x ~= x then return "NaN" end
  if x == math.huge then return "Infinity" end
  if x == -math.huge then return "-Infinity" end
  return number_text(x)
end

local function structure_file(path, entries)
  local blocks = {}
  for i, entry in ipairs(entries) do
    local vertices, faces = {}, {}
    for k, p in ipairs(entry.vertices) do
      vertices[k] = ("[%s, %s, %s]"):format(json_number(p[1]), json_number(p[2]), json_number(p[3]))
    end
    for k, face in ipairs(entry.faces) do faces[k] = "[" .. zero_based(face):gsub(" ", ", ") .. "]" end
    blocks[i] = ('{"name": "%s", "support": %s, "density": %s, "vertices": [%s], "faces": [%s]}')
      :format(entry.name, tostring(entry.support or false), json_number(entry.density or 2400),
              table.concat(vertices, ", "), table.concat(faces, ", "))
  end
  return lines_to(path, { '{"format": "ashlar-structure", "version": 1, "blocks": [',
                          table.concat(blocks, ",\n"), "]}" })
end

local FORMATS = { "obj", "off", "ply", "stl" }
-- What each format calls the object: OBJ its "o" name; OFF, PLY and
-- binary STL have no names, so the importer numbers the objects.
local OBJECT_NAME = { obj = "keystone", off = "object 1", ply = "object 1", stl = "object 1" }

local files_written = 0

local function file_of(format, solid)
  files_written = files_written + 1
  return writers[format](("%s/solid_%d.%s"):format(folder, files_written, format), solid)
end

------------------------------------------------------------------------
-- Expectations
------------------------------------------------------------------------

local function block_of(solid, name)
  return ashlar.block{ vertices = solid.vertices, faces = solid.faces, name = name }
end

-- The error through ashlar.block, named and unnamed.
local function expect_block_error(solid, defect)
  expect_error({ "block 'keystone' is not a valid block: " .. defect }, block_of, solid, "keystone")
  expect_error({ "unnamed block is not a valid block: " .. defect }, block_of, solid)
end

-- The error through ashlar.import; `defect` is a fragment or a function of
-- the format giving one.
local function expect_import_error(solid, formats, defect)
  for _, format in ipairs(formats) do
    local path = file_of(format, solid)
    local name = OBJECT_NAME[format]
    local wanted = type(defect) == "function" and defect(format) or defect
    expect_error({ ("object '%s' in '%s': "):format(name, path), wanted }, ashlar.import, path)
  end
end

local function expect_import_volume(solid, formats, volume, relative)
  for _, format in ipairs(formats) do
    local s = ashlar.import(file_of(format, solid))
    assert.are.equal(1, #s)
    support.near(s:block(1):volume(), volume, relative * volume, format)
  end
end

-- A defect as a structure file names it: its vertices and faces by their
-- 0-based places in the file, as the paths do ("blocks[0].faces[1]"), where
-- ashlar.block counts them from 1 ("vertices 1 and 2", "face 2").
local function in_file_terms(text)
  local function pair(kind)
    return function(a, b) return ("%s[%d] and %s[%d]"):format(kind, a - 1, kind, b - 1) end
  end
  text = text:gsub("vertices (%d+) and (%d+)", pair("vertices")):gsub("faces (%d+) and (%d+)", pair("faces"))
  text = text:gsub("vertex (%d+)", function(i) return ("vertices[%d]"):format(i - 1) end)
  return (text:gsub("face (%d+)", function(i) return ("faces[%d]"):format(i - 1) end))
end

local function expect_load_error(solid, fragments)
  local path = structure_file(folder .. "/structure.json",
    { { name = "keystone", vertices = solid.vertices, faces = solid.faces } })
  local wanted = { path .. ": " }
  for _, fragment in ipairs(fragments) do wanted[#wanted + 1] = in_file_terms(fragment) end
  expect_error(wanted, ashlar.load, path)
end

local function invalid(defect) return "block 'keystone' is not a valid block: " .. defect end

local OPEN = "open surface: the edge between vertices %d and %d belongs to face %d only "
  .. "(expected a closed surface: every edge shared by two faces)"
local ORIENTATION = "inconsistent face orientation: face %d and face %d run the edge between "
  .. "vertices %d and %d in the same direction (expected every face counter-clockwise seen from "
  .. "outside, so that neighbours run a shared edge in opposite directions)"
local INVERTED = "inverted: its faces point inward (list each face's vertices counter-clockwise "
  .. "seen from outside)"
local ZERO_VOLUME = "zero volume: its vertices are flat or collapsed (expected a solid with volume)"
local NOT_FINITE = "expected finite coordinates, not NaN or infinity"

------------------------------------------------------------------------
-- Bad solids, door by door
------------------------------------------------------------------------

describe("bad geometry", function()
  teardown(function() support.remove_folder(folder) end)

  describe("solids", function()
    it("an open mesh (a face missing) is refused, naming the edge and the face it belongs to", function()
      expect_block_error(solids.open, OPEN:format(1, 2, 2))
      expect_import_error(solids.open, FORMATS, "(expected a closed surface: every edge shared by two faces)")
      expect_load_error(solids.open, { "blocks[0] ('keystone'): ", invalid(OPEN:format(1, 2, 2)) })
      expect_error({ "the edge between vertices[0] and vertices[1] belongs to faces[1] only" }, ashlar.load,
        structure_file(folder .. "/open.json", { { name = "keystone", vertices = solids.open.vertices,
                                                   faces = solids.open.faces } }))
    end)

    it("a block with every face inward is refused as inverted", function()
      expect_block_error(solids.inverted, INVERTED)
      expect_import_error(solids.inverted, FORMATS, "is not a valid block: " .. INVERTED)
      expect_load_error(solids.inverted, { "blocks[0] ('keystone'): ", invalid(INVERTED) })
    end)

    it("one flipped face is refused, naming it and its neighbour", function()
      expect_block_error(solids.one_face_flipped, ORIENTATION:format(2, 3, 5, 6))
      -- Mesh files: faces in the file's order, vertices by their coordinates
      -- (OBJ repeats vertices per face corner, so it finds another edge of
      -- the flipped face first; STL faces are the writer's triangles).
      local ORIENTATION_IN_FILE = "inconsistent face orientation: face %d and face %d run the edge between "
        .. "vertex %s and vertex %s in the same direction"
      expect_import_error(solids.one_face_flipped, FORMATS, function(format)
        return ({ obj = ORIENTATION_IN_FILE:format(2, 4, "(0, 1, 1)", "(1, 1, 1)"),
                  off = ORIENTATION_IN_FILE:format(2, 3, "(0, 0, 1)", "(1, 0, 1)"),
                  ply = ORIENTATION_IN_FILE:format(2, 3, "(0, 0, 1)", "(1, 0, 1)"),
                  stl = "inconsistent face orientation: face 3 (merged with face 4) and face 7 (merged with "
                    .. "face 8) run the edge between vertex (0, 1, 1) and vertex (1, 1, 1) in the same direction" })[format]
          .. " (expected every face counter-clockwise"
      end)
      expect_load_error(solids.one_face_flipped, { invalid(ORIENTATION:format(2, 3, 5, 6)) })
    end)

    it("a flat block (zero volume, every face with area) is refused", function()
      expect_block_error(solids.flat, ZERO_VOLUME)
      -- Repair merges the three coplanar upper faces into one triangle: what
      -- is left cannot close a solid, and the message says how it came about.
      expect_import_error(solids.flat, FORMATS, "is not a valid block: needs at least 4 vertices, got 3; welding "
        .. "vertices closer than 1.41421e-09 m, dropping flat faces and merging coplanar ones made the mesh's 4 faces and ")
      expect_load_error(solids.flat, { invalid(ZERO_VOLUME) })
    end)

    -- Refused from the API, where they are mistakes; repaired from mesh
    -- files, where exporters leave them.
    for _, case in ipairs{
      { "coincident vertices are refused from the API and welded from mesh files", solids.coincident,
        "vertices 8 and 9 coincide: expected distinct points (faces that share a corner use one vertex index for it)" },
      { "a corner repeated in a face is refused from the API and dropped from mesh files", solids.repeated_corner,
        "face 1 uses vertex 4 twice: expected each corner of a face once" },
      -- In STL the zero-area face and the fan triangle of its neighbour lie
      -- back to back; both go and the surface stays closed.
      { "a zero-area face is refused from the API and dropped from mesh files", solids.zero_area_face,
        "face 3 has zero area: expected a polygon whose vertices do not all lie on one line" },
    } do
      local title, solid, defect = table.unpack(case)
      it(title, function()
        expect_block_error(solid, defect)
        expect_load_error(solid, { invalid(defect) })
        expect_import_volume(solid, FORMATS, 1, 1e-12)
      end)
    end

    it("a non-planar face is refused, with the distance and the tolerance; STL triangles are planar", function()
      local defect = "face 2 is not planar: its vertex 5 is 0.0495074 m off the face's plane "
        .. "(allowed: 1.85472e-06 m)"
      expect_block_error(solids.non_planar, defect)
      expect_load_error(solids.non_planar, { invalid(defect) })
      -- The face the file lists second; its vertex by its coordinates.
      expect_import_error(solids.non_planar, { "obj", "off", "ply" },
        "is not a valid block: face 2 is not planar: its vertex (0, 0, 1) is 0.0495074 m off the face's plane")
      -- The same points as triangles bound a valid solid: the quad's two
      -- triangles add the tetrahedron over the lifted corner.
      expect_import_volume(solids.non_planar, { "stl" }, 1 + 0.2 / 3, 1e-6)
    end)

    it("a self-intersecting surface is refused, naming two faces that cross", function()
      local defect = "self-intersecting: faces 1 and 2 cross each other (expected a surface that does not cross "
        .. "or touch itself)"
      expect_block_error(solids.self_intersecting, defect)
      expect_load_error(solids.self_intersecting, { invalid(defect) })
      expect_import_error(solids.self_intersecting, { "obj", "off", "ply" },
        "is not a valid block: self-intersecting: face 1 and face 2 cross each other")
      expect_import_error(solids.self_intersecting, { "stl" }, "is not a valid block: self-intersecting: face 3 and face 1 (merged with face 2) cross each other")
    end)

    it("an edge of more than two faces is refused", function()
    local defect = "non-manifold surface: the edge between vertices 4 and 8 belongs to 4 faces (expected two)"
    expect_block_error(solids.non_manifold, defect)
    expect_load_error(solids.non_manifold, { invalid(defect) })
    expect_import_error(solids.non_manifold, FORMATS, "is not a valid block: non-manifold surface: ")
  end)

  it("a block in separate pieces is refused: they would move as one body", function()
      local defect = "its surface is in separate pieces (face 1 and face 7 are not joined by any path of shared "
        .. "edges): expected one connected solid; make each piece a block of its own"
      expect_block_error(solids.two_pieces, defect)
      expect_load_error(solids.two_pieces, { invalid(defect) })
      expect_import_error(solids.two_pieces, FORMATS, "is not a valid block: its surface is in separate pieces")
      -- OBJ readers merge objects of one name into one mesh.
      local twins = lines_to(folder .. "/twins.obj", { "o pier", "v 0 0 0", "v 1 0 0", "v 0 1 0", "v 0 0 1",
        "f 1 3 2", "f 1 2 4", "f 2 3 4", "f 3 1 4", "o pier", "v 2 0 0", "v 3 0 0", "v 2 1 0", "v 2 0 1",
        "f 5 7 6", "f 5 6 8", "f 6 7 8", "f 7 5 8" })
      expect_error({ "object 'pier' in '" .. twins .. "': block 'pier' is not a valid block: its surface is in "
        .. "separate pieces" }, ashlar.import, twins)
    end)

    it("a face whose outline crosses itself is refused", function()
      local defect = "face 1 has an outline that crosses itself: expected a simple polygon"
      expect_block_error(solids.crossed_outline, defect)
      expect_load_error(solids.crossed_outline, { invalid(defect) })
      expect_error({ defect }, ashlar.prism, { { 0, 0, 0 }, { 3, 1, 0 }, { 3, 0, 0 }, { 0, 2, 0 } }, { 0, 0, 1 })
      expect_import_error(solids.crossed_outline, { "obj", "off", "ply" }, "is not a valid block: " .. defect)
    end)

    it("NaN and infinite coordinates are refused, naming the vertex", function()
      for _, case in ipairs{ { solids.nan, "nan", "[3][1]", '"NaN"' }, { solids.inf, "inf", "[3][1]", '"Infinity"' },
                             { solids.minus_inf, "-inf", "[3][2]", '"-Infinity"' } } do
        local solid, shown, at, json = table.unpack(case)
        expect_error({ ("bad argument #1 to 'block' (vertices%s: expected a finite number, got %s)")
          :format(at, shown) }, block_of, solid, "keystone")
        expect_import_error(solid, FORMATS, NOT_FINITE)
        expect_load_error(solid, { "blocks[0].vertices[2]: expected 3 finite numbers, got array [", json })
      end
      expect_import_error(solids.nan, { "obj" }, "vertex (nan, 1, 0): " .. NOT_FINITE
        .. " (faces counted from 1 in the object's order in the file, vertices by their coordinates in the file)")
      expect_error({ "bad argument #1 to ", "(points[4][3]: expected a finite number, got nan)" },
        ashlar.hull, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 0 / 0 } })
      expect_error({ "bad argument #2 to ", "(vector[3]: expected a finite number, got inf)" },
        ashlar.prism, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { 0, 0, math.huge })
    end)

    it("blocks of 1e-9 m and 1e9 m are valid through every door", function()
      for _, case in ipairs{ { solids.tiny, 1e-27 }, { solids.huge, 1e27 } } do
        local solid, volume = table.unpack(case)
        support.near(block_of(solid, "keystone"):volume(), volume, 1e-12 * volume)
        -- float32 files keep about 7 digits.
        expect_import_volume(solid, FORMATS, volume, 1e-6)
        local path = structure_file(folder .. "/scaled.json",
          { { name = "keystone", vertices = solid.vertices, faces = solid.faces } })
        support.near(ashlar.load(path):block(1):volume(), volume, 1e-12 * volume)
      end
    end)

    it("blocks beyond 1e-30 m to 1e30 m are refused by size; mesh files lose them to float32 first", function()
      expect_block_error(solids.too_small, "its size (bounding-box diagonal) is 1.73205e-200 m: expected 1e-30 "
        .. "to 1e+30 m, where its volume and moments stay within double range")
      expect_block_error(solids.too_large, "its size (bounding-box diagonal) is 1.73205e+200 m")
      expect_load_error(solids.too_large, { invalid("its size (bounding-box diagonal) is 1.73205e+200 m") })
      -- In float32 1e-200 is 0 and 1e200 is infinite.
      expect_import_error(solids.too_small, FORMATS, "is not a valid block: needs at least 4 vertices, got 0; "
        .. "welding vertices closer than 0 m, dropping flat faces and merging coplanar ones made the mesh's ")
      expect_import_error(solids.too_large, FORMATS, NOT_FINITE)
    end)

    it("a block far from the origin is valid, but a mesh file's float32 coordinates are too coarse for it", function()
      support.near(block_of(solids.far_away, "keystone"):volume(), 1, 1e-6)
      local path = structure_file(folder .. "/far.json",
        { { name = "keystone", vertices = solids.far_away.vertices, faces = solids.far_away.faces } })
      support.near(ashlar.load(path):block(1):volume(), 1, 1e-6)
      expect_import_error(solids.far_away, FORMATS, "; mesh files are read in single precision, in steps of about "
        .. "119 m this far from the origin, coarse for an object ")
    end)
  end)

  ------------------------------------------------------------------------
  -- Constructors: zero or negative sizes and densities
  ------------------------------------------------------------------------

  describe("sizes and densities", function()
    it("refuses zero and negative box sizes, naming the box", function()
      expect_error({ "box size must be three positive finite numbers (m), got (0, 1, 1)" },
        ashlar.box, { size = { 0, 1, 1 } })
      expect_error({ "box 'lintel' size must be three positive finite numbers (m), got (1, -1, 1)" },
        ashlar.box, { size = { 1, -1, 1 }, name = "lintel" })
      expect_error({ "prism vector must be finite and non-zero, got (0, 0, 0)" },
        ashlar.prism, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }, { 0, 0, 0 })
      expect_error({ "hull: points are coplanar: a hull needs volume" },
        ashlar.hull, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 } })
    end)

    it("refuses zero, negative and NaN densities through every door", function()
      local unit = { size = { 1, 1, 1 } }
      for _, case in ipairs{ { 0, "expected a number > 0, got 0" }, { -5, "expected a number > 0, got -5" },
                             { 0 / 0, "expected a finite number, got nan" } } do
        local density, problem = table.unpack(case)
        expect_error({ "bad argument #1 to ", "(density: " .. problem }, ashlar.box,
          { size = unit.size, density = density })
        expect_error({ "bad argument #1 to ", "(density: " .. problem }, ashlar.block,
          { vertices = CUBE_VERTICES, faces = CUBE_FACES, density = density })
        expect_error({ "bad argument #1 to 'with' (density: " .. problem },
          function() return ashlar.box(unit):with{ density = density } end)
        expect_error({ "bad argument #2 to ", "(density: " .. problem }, ashlar.import,
          file_of("obj", cube()), { density = density })
      end
      for _, density in ipairs{ 0, -5 } do
        local path = structure_file(folder .. "/density.json",
          { { name = "keystone", vertices = CUBE_VERTICES, faces = CUBE_FACES, density = density } })
        expect_error({ path .. ": blocks[0].density: must be positive (kg/m^3)" }, ashlar.load, path)
      end
    end)

    it("refuses zero and negative model dimensions, naming the generator and the option", function()
      expect_error({ "models.arch: thickness: must be > 0, got 0" }, models.arch, { thickness = 0 })
      expect_error({ "models.arch: radius: must be > 0, got -5" }, models.arch, { radius = -5 })
      expect_error({ "models.wall: brick[1]: must be > 0, got 0" }, models.wall, { brick = { 0, 0.07 } })
      expect_error({ "models.arch: density: must be > 0, got 0" }, models.arch, { density = 0 })
    end)
  end)

  ------------------------------------------------------------------------
  -- Builders asked for absurd counts
  ------------------------------------------------------------------------

  describe("huge counts", function()
    it("refuses a count above 1,000,000 before building anything", function()
      local clock = ashlar.clock()
      support.expect_generator_error({ "models.arch: voussoirs: must be <= 1000000 (the most blocks a model may have), got 1e+09" },
        models.arch, { voussoirs = 1e9 })
      support.expect_generator_error({ "models.column: drums: must be <= 1000000" }, models.column, { drums = 2 ^ 53 })
      support.expect_generator_error({ "models.stack: blocks: must be <= 1000000" }, models.stack, { blocks = 1e300 })
      support.expect_generator_error({ "models.arch: voussoirs: expected a finite number" }, models.arch, { voussoirs = 0 / 0 })
      support.expect_generator_error({ "models.dome: meridians x parallels = 100000 x 100000 makes 10000000000 blocks, "
        .. "more than the 1000000 a model may have" }, models.dome, { meridians = 100000, parallels = 100000 })
      support.expect_generator_error({ "models.wall: 4166666667 bricks per course x 10 courses makes 41666666670 blocks" },
        models.wall, { length = 1e9 })
      support.expect_generator_error({ "models.barrel_vault: voussoirs = 24 with courses = 1000000 makes 24000024 blocks" },
        models.barrel_vault, { courses = 1e6 })
      support.expect_generator_error({ "models.groin_vault: voussoirs = 1000000 with courses = 4 makes" },
        models.groin_vault, { voussoirs = 1e6 })
      support.expect_generator_error({ "models.arch_bridge: spans = 1000000 with voussoirs = 26 and pier_courses = 4 makes" },
        models.arch_bridge, { spans = 1e6 })
      -- Refused up front: building even a thousandth of these would take minutes.
      assert.is_true(ashlar.clock() - clock < 5)
    end)

    it("refuses an FEA refinement beyond its limit", function()
      expect_error({ "refine: expected a whole number from 1 to 64, got 1000000000" },
        ashlar.fea, models.column{ drums = 1 }, { refine = 1e9 })
    end)
  end)

  ------------------------------------------------------------------------
  -- Structures and their analyses
  ------------------------------------------------------------------------

  local function box(size, center, name)
    return ashlar.box{ size = size, center = center, name = name }
  end

  local function on_ground(...)
    local s = ashlar.structure()
    s:add(box({ 6, 2, 1 }, { 0, 0, -0.5 }, "ground"), { support = true })
    for _, b in ipairs{ ... } do s:add(b) end
    return s
  end

  -- Every analysis of s refuses it with the same fragments; the FEA too
  -- unless the structure is no FEA model (a block that is no hexahedron).
  local function expect_every_analysis_error(s, fragments, without_fea)
    local analyses = { analyze = "analysis: ", load_factor = "analysis: ", friction_demand = "analysis: ",
                       fea = not without_fea and "fea: " or nil }
    for analysis, prefix in pairs(analyses) do
      local wanted = { prefix }
      for _, fragment in ipairs(fragments) do wanted[#wanted + 1] = fragment end
      expect_error(wanted, ashlar[analysis], s)
    end
  end

  -- An L-shaped prism (non-convex) standing on the ground, its notch open to
  -- +x and +z: the corner at x = 0..1, z = 1..2.
  local function l_block()
    return ashlar.prism({ { -1, -0.5, 0 }, { 1, -0.5, 0 }, { 1, -0.5, 1 }, { 0, -0.5, 1 }, { 0, -0.5, 2 },
                          { -1, -0.5, 2 } }, { 0, 1, 0 }, { name = "L" })
  end

  describe("structures", function()
    it("refuses interpenetrating blocks in every analysis, naming both and the depth", function()
      local side_by_side = on_ground(box({ 1, 1, 1 }, { 0, 0, 0.5 }, "left"), box({ 1, 1, 1 }, { 0.5, 0, 0.5 }, "right"))
      expect_every_analysis_error(side_by_side, { "block 2 ('left') and block 3 ('right') overlap by 0.5 m "
        .. "(expected blocks that touch along faces, not interpenetrate; contact tolerance " })
      local sunk = on_ground(box({ 1, 1, 1 }, { 0, 0, 0.3 }, "sunk"))
      expect_every_analysis_error(sunk, { "block 1 ('ground') and block 2 ('sunk') overlap by 0.2 m" })
      -- A non-convex block: a box pushed 0.1 m into the L's corner overlaps;
      -- one sitting in it only touches.
      local pushed = on_ground(l_block(), box({ 1, 1, 1 }, { 0.4, 0, 1.5 }, "pushed"))
      expect_every_analysis_error(pushed, { "block 2 ('L') and block 3 ('pushed') overlap by 0.1 m" }, true)
      local seated = on_ground(l_block(), box({ 1, 1, 1 }, { 0.5, 0, 1.5 }, "seated"))
      assert.is_true(ashlar.analyze(seated).stable)
      assert.are.equal(3, #seated:interfaces())
    end)

    it("lists the first three overlapping pairs and counts the rest", function()
      local s = on_ground()
      for i = 1, 5 do s:add(box({ 1, 1, 1 }, { 0.1 * i, 0, 0.3 }, "b" .. i)) end
      expect_error({ "analysis: block 1 ('ground') and block 2 ('b1') overlap by 0.2 m; block 1 ('ground') and "
        .. "block 3 ('b2') by 0.2 m; block 1 ('ground') and block 4 ('b3') by 0.2 m; and 12 more pairs" },
        ashlar.analyze, s)
      -- s:overlaps() lists them all: the ground with each box, each box with each other.
      local overlaps = s:overlaps()
      assert.are.equal(15, #overlaps)
      assert.are.equal(1, overlaps[1].a)
      assert.are.equal(2, overlaps[1].b)
      support.near(overlaps[1].depth, 0.2, 1e-12)
      support.near(overlaps[15].depth, 0.9, 1e-12, "b4 and b5")
    end)

    it("reports a block touching nothing as floating, with its index", function()
      local s = on_ground(box({ 1, 1, 1 }, { 0, 0, 0.5 }, "sitting"), box({ 1, 1, 1 }, { 0, 0, 3 }, "floater"))
      local r = ashlar.analyze(s)
      assert.are.same({ 3 }, r.floating)
      assert.is_true(r.blocks[3].floating)
      assert.is_false(r.blocks[2].floating)
      assert.is_false(r.stable)
      assert.are.equal(math.huge, r.infeasibility)
      local lf = ashlar.load_factor(s)
      assert.are.equal("floating", lf.status)
      assert.is_true(lf.factor ~= lf.factor)
      local fd = ashlar.friction_demand(s)
      assert.are.equal("floating", fd.status)
      assert.are.equal(math.huge, fd.friction)
      assert.are.equal("mechanism", ashlar.fea(s).status)
    end)

    it("reports every block of a structure with no support as floating", function()
      local s = ashlar.structure()
      s:add(box({ 1, 1, 1 }, { 0, 0, 0.5 }, "a"))
      s:add(box({ 1, 1, 1 }, { 0, 0, 1.5 }, "b"))
      local r = ashlar.analyze(s)
      assert.are.same({ 1, 2 }, r.floating)
      assert.is_false(r.stable)
      assert.are.equal("floating", ashlar.load_factor(s).status)
      assert.are.equal("floating", ashlar.friction_demand(s).status)
      assert.are.equal("mechanism", ashlar.fea(s).status)
    end)

    it("refuses an empty structure and one of supports only", function()
      expect_every_analysis_error(ashlar.structure(), { "the structure is empty: expected at least one block that "
        .. "is not a support (add blocks with s:add)" })
      expect_every_analysis_error(on_ground(), { "all 1 blocks are supports: expected at least one block that is not a support" })
    end)

    it("refuses a duplicate block name, naming the block that has it", function()
      -- (Two OBJ objects of one name: see "a block in separate pieces".)
      local s = ashlar.structure()
      s:add(box({ 1, 1, 1 }, { 0, 0, 0.5 }), { name = "pier" })
      expect_error({ "structure add: the name 'pier' is already used by block 1; block names must be unique" },
        function() s:add(box({ 1, 1, 1 }, { 0, 0, 1.5 }), { name = "pier" }) end)
      -- Blocks named alike without an explicit name get their index appended.
      s:add(box({ 1, 1, 1 }, { 0, 0, 1.5 }, "pier"))
      assert.are.equal("pier 2", s:name(2))
      local path = structure_file(folder .. "/names.json",
        { { name = "pier", vertices = CUBE_VERTICES, faces = CUBE_FACES },
          { name = "pier", vertices = scaled(CUBE_VERTICES, 1, 1), faces = CUBE_FACES } })
      expect_error({ path .. ": blocks[1] ('pier'): structure add: the name 'pier' is already used by block 1" },
        ashlar.load, path)
    end)

    it("refuses a non-convex or non-hexahedral block in the FEA, naming it", function()
      local l = on_ground(l_block())
      expect_error({ "block 2 ('L') is not a hexahedron (12 vertices): the FEA meshes each block as 8-node hexahedra" },
        ashlar.fea, l)
      -- A prism over an arrowhead: a valid hexahedron (planar faces) that is
      -- not convex, so its trilinear map folds at the reflex corner.
      local dart = ashlar.prism({ { 0, 0, 0 }, { 2, 0, 0 }, { 0.5, 0.5, 0 }, { 0, 2, 0 } }, { 0, 0, 1 }, { name = "dart" })
      expect_error({ "block 2 ('dart') is a hexahedron whose trilinear map folds (a corner's Jacobian is not positive): "
        .. "its faces are twisted or it is not convex" }, ashlar.fea, on_ground(dart))
    end)

    it("analyses a whole model scaled to 1e-9 m and to 1e9 m alike", function()
      for _, k in ipairs{ 1e-9, 1, 1e9 } do
        local s = models.arch{ radius = 5 * k, thickness = 0.6 * k, depth = k }
        local r = ashlar.analyze(s)
        assert.is_true(r.stable, "scale " .. k)
        assert.are.equal("converged", r.status)
        local lf = ashlar.load_factor(s)
        assert.are.equal("optimal", lf.status)
        support.near(lf.factor, ashlar.load_factor(models.arch{}).factor, 1e-6, "load factor at scale " .. k)
      end
      -- The FEA's displacements follow the load: at 1e9 m self-weight strains
      -- the stone by rho g L / E = 1e3, far beyond max_displacement.
      local s = models.column{ drums = 2, width = 1e8, depth = 1e8, height = 1e9 }
      assert.are.equal("mechanism", ashlar.fea(s).status)
    end)
  end)
end)
