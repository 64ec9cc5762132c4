-- Contacts that do not depend on how a structure is turned, tolerances that
-- never lose a joint, warped joints that meet themselves, and supports given
-- as open planar surfaces. Verdicts are checked against an LP that shares
-- no code with ashlar's analysis (tests/tools/equilibrium_lp.py).
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local near = support.near

-- The structure turned about `axis` by `angle` through the origin, then
-- moved by `offset`: every block, supports kept.
local function moved(s, axis, angle, offset)
  local copy = ashlar.structure()
  for i = 1, #s do
    copy:add(s:block(i):rotated(axis, angle, { 0, 0, 0 }):translated(offset),
      { support = s:is_support(i), name = s:name(i) })
  end
  return copy
end

-- The contacts as sorted "a-b" keys with their areas.
local function contact_areas(s, contact)
  local list = {}
  for _, f in ipairs(s:interfaces(contact)) do list[#list + 1] = { key = f.a .. "-" .. f.b, area = f.area } end
  table.sort(list, function(x, y) return x.key < y.key or (x.key == y.key and x.area < y.area) end)
  return list
end

-- The number of block pairs in contact.
local function pair_count(s, contact)
  local pairs_seen, count = {}, 0
  for _, f in ipairs(s:interfaces(contact)) do
    local key = f.a .. "-" .. f.b
    if not pairs_seen[key] then pairs_seen[key], count = true, count + 1 end
  end
  return count
end

-- Two boxes 0.20 x 0.06 x 0.10 m, the lower a support, the upper resting on
-- it flush across its whole 0.20 x 0.06 face, both turned about z.
local function narrow_joint(angle)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 0.20, 0.06, 0.10 }, center = { 0, 0, -0.05 } }:rotated({ 0, 0, 1 }, angle),
    { support = true, name = "bed" })
  s:add(ashlar.box{ size = { 0.20, 0.06, 0.10 }, center = { 0, 0, 0.05 } }:rotated({ 0, 0, 1 }, angle),
    { name = "block" })
  return s
end

-- A stack of narrow blocks (0.3 x 0.04 x 0.1 m) each shifted along x.
local function narrow_stack()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 0.6, 0.2, 0.1 }, center = { 0, 0, -0.05 } }, { support = true, name = "ground" })
  for k = 1, 5 do
    s:add(ashlar.box{ size = { 0.3, 0.04, 0.1 }, center = { 0.01 * k, 0, 0.1 * k - 0.05 } })
  end
  return s
end

describe("contact detection", function()
  it("finds a narrow joint however it is turned and whatever the tolerance", function()
    for degrees = 0, 90, 5 do
      local s = narrow_joint(math.rad(degrees))
      for tolerance = 0.01, 0.1001, 0.01 do
        local found = s:interfaces{ tolerance = tolerance }
        assert(#found == 1, ("%d degrees, tolerance %.2f: %d interfaces, expected 1"):format(degrees, tolerance, #found))
        near(found[1].area, 0.012, 1e-9 * 0.012, ("%d degrees, tolerance %.2f: area"):format(degrees, tolerance))
        local r = ashlar.analyze(s, { contact_tolerance = tolerance })
        assert(r.stable, ("%d degrees, tolerance %.2f: %s"):format(degrees, tolerance, tostring(r)))
      end
    end
  end)

  it("keeps a joint narrower than min_width out, and a wider one in, at any turn", function()
    for degrees = 0, 90, 15 do
      local s = narrow_joint(math.rad(degrees))
      assert(#s:interfaces{ tolerance = 0.05, min_width = 0.0599 } == 1, degrees .. " degrees")
      assert(#s:interfaces{ tolerance = 0.05, min_width = 0.0601 } == 0, degrees .. " degrees")
    end
  end)

  it("gives the same contacts and verdict after any rigid motion", function()
    local cases = {
      { "arch", models.arch{ voussoirs = 16 } },
      { "wall", models.wall{ length = 1.44, height = 0.35 } },
      { "dome", models.dome{ meridians = 8, parallels = 5 } },
      { "running-bond vault", models.barrel_vault{ voussoirs = 10, courses = 3, bond = "running" } },
      { "narrow stack", narrow_stack() },
    }
    local motions = {
      { { 1, 0, 0 }, 0.7, { 0.3, -2, 5 } },
      { { 0, 1, 0 }, -1.1, { -4, 1, 0.5 } },
      { { 0, 0, 1 }, 2.3, { 10, 20, -3 } },
      { { 0.3, -0.5, 0.8 }, 0.9, { 1.5, 2.5, 3.5 } },
      { { -0.7, 0.2, 0.1 }, 2.9, { -7, 0, 2 } },
    }
    for _, case in ipairs(cases) do
      local name, s = case[1], case[2]
      local reference = contact_areas(s)
      local verdict = ashlar.analyze(s, { friction = 0.7 }).stable
      assert(#reference > 0, name)
      for m, motion in ipairs(motions) do
        local copy = moved(s, motion[1], motion[2], motion[3])
        local found = contact_areas(copy)
        assert(#found == #reference, ("%s, motion %d: %d interfaces, expected %d"):format(name, m, #found, #reference))
        for k, f in ipairs(found) do
          assert(f.key == reference[k].key, ("%s, motion %d: interface %d is %s, expected %s"):format(
            name, m, k, f.key, reference[k].key))
          near(f.area, reference[k].area, 1e-9 * reference[k].area, ("%s, motion %d, interface %s"):format(name, m, f.key))
        end
        -- Gravity stays along -z, so only motions about z keep the loads.
        if motion[1][1] == 0 and motion[1][2] == 0 then
          assert(ashlar.analyze(copy, { friction = 0.7 }).stable == verdict, name .. ": verdict after motion " .. m)
        end
      end
    end
  end)

  it("never loses a joint as the tolerance grows (1e-6 to 20 % of the block size)", function()
    local cases = {
      { "arch", models.arch{ voussoirs = 12 }, 0.6 },
      { "dome", models.dome{ meridians = 8, parallels = 5 }, 0.5 },
      { "imperfect vault", models.perturbed(models.barrel_vault{ voussoirs = 10, courses = 3, bond = "running" },
        { amount = 0.01 }), 0.45 },
      { "narrow stack", narrow_stack(), 0.04 },
    }
    for _, case in ipairs(cases) do
      local name, s, size = case[1], case[2], case[3]
      local previous, previous_tolerance = 0, 0
      for k = 0, 24 do
        local tolerance = 1e-6 * size * (0.2 / 1e-6) ^ (k / 24)
        local count = pair_count(s, { tolerance = tolerance })
        assert(count >= previous, ("%s: %d pairs at tolerance %.3g m, %d at %.3g m"):format(
          name, count, tolerance, previous, previous_tolerance))
        previous, previous_tolerance = count, tolerance
      end
    end
  end)
end)

-- A unit cube whose corner (1, 1, 1) is raised by `rise`: its top face is
-- warped. `above` gives the block on that face instead (up to z = 2), its
-- bottom face's loop started at corner `start` (1-4).
local function warped_block(rise, above, start)
  local corners = { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 + rise }, { 0, 1, 1 } }
  if not above then
    return ashlar.block{
      vertices = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, corners[1], corners[2], corners[3], corners[4] },
      faces = { { 1, 4, 3, 2 }, { 5, 6, 7, 8 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 4, 8, 7 }, { 4, 1, 5, 8 } },
      planarity = 0.05 }
  end
  local bottom = { 4, 3, 2, 1 }  -- downwards
  local loop = {}
  for k = 1, 4 do loop[k] = bottom[(k + start - 2) % 4 + 1] end
  return ashlar.block{
    vertices = { corners[1], corners[2], corners[3], corners[4], { 0, 0, 2 }, { 1, 0, 2 }, { 1, 1, 2 }, { 0, 1, 2 } },
    faces = { loop, { 5, 6, 7, 8 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 4, 8, 7 }, { 4, 1, 5, 8 } },
    planarity = 0.05 }
end

describe("warped faces", function()
  it("bound the solid by the fan about their centre, whichever corner a loop starts at", function()
    -- Over the unit square the fan's four triangles give the volume as the
    -- height of the centre: 1 + rise / 4 (a fan from a corner would give
    -- 1 + rise / 3 or 1 + rise / 6, by the diagonal it takes).
    local rise = 0.1
    near(warped_block(rise):volume(), 1 + rise / 4, 1e-14, "below the warped face")
    for start = 1, 4 do
      near(warped_block(rise, true, start):volume(), 1 - rise / 4, 1e-14, "above, loop from corner " .. start)
    end
  end)

  it("agree with the same surface given as triangles", function()
    local b = warped_block(0.1)
    local v = b:vertices()
    local c = { 0.5, 0.5, 1.025 }
    local vertices, faces = {}, {}
    for k = 1, 8 do vertices[k] = v[k] end
    vertices[9] = c
    local top = { 5, 6, 7, 8 }
    for k = 1, 4 do faces[#faces + 1] = { 9, top[k], top[k % 4 + 1] } end
    for k, face in ipairs(b:faces()) do
      if k ~= 2 then faces[#faces + 1] = face end
    end
    local triangles = ashlar.block{ vertices = vertices, faces = faces }
    near(b:volume(), triangles:volume(), 1e-14, "volume")
    for k = 1, 3 do near(b:centroid()[k], triangles:centroid()[k], 1e-14, "centroid " .. k) end
  end)

  it("meet as one joint: no overlap within the warp, and the stack stands", function()
    for start = 1, 4 do
      local s = ashlar.structure()
      s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0.5, 0.5, -0.5 } }, { support = true, name = "ground" })
      s:add(warped_block(0.1), { name = "below" })
      s:add(warped_block(0.1, true, start), { name = "above" })
      local overlaps = s:overlaps{ tolerance = 1e-4 }
      assert(#overlaps == 0, ("loop from corner %d: %d overlaps, the first %.3g m deep"):format(
        start, #overlaps, overlaps[1] and overlaps[1].depth or 0))
      local r = ashlar.analyze(s, { contact_tolerance = 1e-4 })
      assert(r.stable, "loop from corner " .. start .. ": " .. tostring(r))
      near(support.free_volume(s), 2, 1e-13, "the two blocks fill the 1 x 1 x 2 prism")
    end
  end)
end)

-- A compas 2 assembly JSON of the nodes { name, support, vertices, faces }
-- (faces 0-based).
local function compas_json(nodes)
  local parts = {}
  for k, node in ipairs(nodes) do
    local vertices, faces = {}, {}
    for i, p in ipairs(node.vertices) do
      vertices[i] = ('"%d":{"x":%.17g,"y":%.17g,"z":%.17g}'):format(i - 1, p[1], p[2], p[3])
    end
    for i, face in ipairs(node.faces) do faces[i] = ('"%d":[%s]'):format(i - 1, table.concat(face, ",")) end
    parts[k] = ('"%d":{"is_support":%s,"block":{"dtype":"compas_assembly.datastructures/Block","data":'
      .. '{"attributes":{"name":"%s"},"vertex":{%s},"face":{%s}}}}'):format(
      k - 1, tostring(node.support), node.name, table.concat(vertices, ","), table.concat(faces, ","))
  end
  return '{"dtype":"compas_assembly.datastructures/Assembly","data":{"graph":{"dtype":"compas.datastructures/Graph",'
    .. '"data":{"node":{' .. table.concat(parts, ",") .. '},"edge":{}}}}}'
end

local CUBE_VERTICES = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } }
local CUBE_FACES = { { 0, 3, 2, 1 }, { 4, 5, 6, 7 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 3, 0, 4, 7 } }

describe("open planar supports", function()
  local folder
  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  -- The ground as one quad (either winding) or as two coplanar triangles.
  local grounds = {
    { "quad facing up", { { -1, -1, 0 }, { 2, -1, 0 }, { 2, 2, 0 }, { -1, 2, 0 } }, { { 0, 1, 2, 3 } } },
    { "quad facing down", { { -1, -1, 0 }, { 2, -1, 0 }, { 2, 2, 0 }, { -1, 2, 0 } }, { { 3, 2, 1, 0 } } },
    { "two triangles", { { -1, -1, 0 }, { 2, -1, 0 }, { 2, 2, 0 }, { -1, 2, 0 } }, { { 0, 1, 2 }, { 0, 2, 3 } } },
  }

  it("bear blocks from a COMPAS assembly as a support would", function()
    for _, ground in ipairs(grounds) do
      local path = folder .. "/ground.json"
      support.write_file(path, compas_json{
        { name = "ground", support = false, vertices = ground[2], faces = ground[3] },
        { name = "cube", support = false, vertices = CUBE_VERTICES, faces = CUBE_FACES },
      })
      local s = ashlar.import(path, { interfaces = "detect" })
      assert(#s == 2 and s:is_support(s:find("ground")) and not s:is_support(s:find("cube")), ground[1])
      local found = s:interfaces()
      assert(#found == 1, ground[1] .. ": " .. #found .. " interfaces")
      near(found[1].area, 1, 1e-12, ground[1] .. ": area")
      local r = ashlar.analyze(s)
      assert(r.stable, ground[1] .. ": " .. tostring(r))
      -- The ground carries the cube's weight, under its centre.
      near(r.interfaces[1].normal_force, 9.81 * 2400, 1e-6 * 9.81 * 2400, ground[1] .. ": reaction")
      local p = r.interfaces[1].center_of_pressure
      near(p[1], 0.5, 1e-9, ground[1] .. ": centre of pressure x")
      near(p[2], 0.5, 1e-9, ground[1] .. ": centre of pressure y")
      near(p[3], 0, 1e-9, ground[1] .. ": on the ground's plane")
    end
  end)

  it("bear blocks from a mesh file, and a block hanging past the edge falls", function()
    for _, overhang in ipairs{ 0, 1.6 } do
      local lines = { "o ground", "v -1 -1 0", "v 2 -1 0", "v 2 2 0", "v -1 2 0", "f 1 2 3 4", "o cube" }
      for _, p in ipairs(CUBE_VERTICES) do lines[#lines + 1] = ("v %g %g %g"):format(p[1] + overhang, p[2], p[3]) end
      for _, face in ipairs(CUBE_FACES) do
        lines[#lines + 1] = ("f %d %d %d %d"):format(face[1] + 5, face[2] + 5, face[3] + 5, face[4] + 5)
      end
      local path = folder .. "/ground.obj"
      support.write_file(path, table.concat(lines, "\n") .. "\n")
      local s = ashlar.import(path)
      assert(s:is_support(s:find("ground")))
      local r = ashlar.analyze(s)
      -- Centroid at x = 0.5 + overhang against the ground's edge at x = 2.
      assert(r.stable == (overhang + 0.5 < 2), "overhang " .. overhang .. ": " .. tostring(r))
      assert(support.independent_verdict(s, 0.7) == r.stable, "overhang " .. overhang .. ": the LP disagrees")
    end
  end)

  it("refuse a bent open surface as before", function()
    local path = folder .. "/bent.obj"
    support.write_file(path, table.concat({ "o bent", "v 0 0 0", "v 1 0 0", "v 1 1 0.5", "v 0 1 0", "v 2 0 0",
      "f 1 2 3", "f 1 3 4", "f 2 5 3" }, "\n") .. "\n")
    support.expect_error({ "bent" }, ashlar.import, path)
  end)
end)
