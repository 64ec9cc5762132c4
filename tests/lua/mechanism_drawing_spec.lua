-- Collapse mechanisms as results: the limit interfaces of ashlar.analyze
-- past the load factor against ashlar.load_factor's and the closed-form
-- four-hinge search (tests/lua/four_hinge.lua), and ashlar.draw of a load
-- factor's result: hinge markers at the pivots, the line of thrust at the
-- factor through them, and the blocks displaced by the mechanism.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local four_hinge = require "four_hinge"
local expect_error, near = support.expect_error, support.near

local NO_SLIDING = { friction = math.huge }

-- Joint j lies between voussoirs j and j + 1 (0: the left support n + 1, n: the right n + 2).
local function joint_of(limit, n)
  return limit.b == n + 1 and 0 or limit.a
end

local function joints_of(limits, n)
  local joints = {}
  for _, limit in ipairs(limits) do joints[#joints + 1] = joint_of(limit, n) end
  table.sort(joints)
  return joints
end

-- Every path element of the SVG: its style (spaces removed) and the points
-- of its d (the end points of M, L and C commands).
local function svg_paths(svg)
  local paths = {}
  for attributes in svg:gmatch("<path([^>]*)/>") do
    local style = (attributes:match('style="([^"]*)"') or ""):gsub(" ", "")
    local d = attributes:match('d="([^"]*)"') or ""
    local numbers = {}
    for v in d:gmatch("[-%d.]+") do numbers[#numbers + 1] = tonumber(v) end
    local points = {}
    for k = 1, #numbers - 1, 2 do points[#points + 1] = { numbers[k], numbers[k + 1] } end
    paths[#paths + 1] = { style = style, d = d, points = points }
  end
  return paths
end

local function with_fill(paths, rgb)
  local found = {}
  for _, p in ipairs(paths) do
    if p.style:find("fill:rgb(" .. rgb .. ")", 1, true) then found[#found + 1] = p end
  end
  return found
end

local function bounds(points)
  local lo, hi = { math.huge, math.huge }, { -math.huge, -math.huge }
  for _, p in ipairs(points) do
    for a = 1, 2 do lo[a], hi[a] = math.min(lo[a], p[a]), math.max(hi[a], p[a]) end
  end
  return lo, hi
end

-- The front elevation's map from (x, z) in metres to image points, found
-- from the image's block outlines (fill colours given) and the model's
-- (x, z) points they draw: equal scale on both axes, y down.
local function elevation_map(paths, fills, model_points)
  local image = {}
  for _, rgb in ipairs(fills) do
    for _, p in ipairs(with_fill(paths, rgb)) do
      for _, q in ipairs(p.points) do image[#image + 1] = q end
    end
  end
  local ilo, ihi = bounds(image)
  local mlo, mhi = bounds(model_points)
  local scale = (ihi[1] - ilo[1]) / (mhi[1] - mlo[1])
  near((ihi[2] - ilo[2]) / (mhi[2] - mlo[2]), scale, 1e-3 * scale, "equal scales")
  return function(x, z) return { ilo[1] + (x - mlo[1]) * scale, ilo[2] + (mhi[2] - z) * scale } end
end

local function model_points(s)
  local points = {}
  for i = 1, #s do
    for _, v in ipairs(s:block(i):vertices()) do points[#points + 1] = { v[1], v[3] } end
  end
  return points
end


-- Point v of block i as the mechanism moves the block by `distance` (the fastest centroid that far): turned
-- about its centroid by distance x |rotation| (Rodrigues' formula), then shifted by distance x velocity.
local function moved_point(s, motion, i, distance, v)
  local m, c = motion[i], s:block(i):centroid()
  local w = m.rotation
  local angle = distance * math.sqrt(w[1] ^ 2 + w[2] ^ 2 + w[3] ^ 2)
  local k = angle > 0 and { w[1] * distance / angle, w[2] * distance / angle, w[3] * distance / angle } or { 0, 0, 0 }
  local cos, sin = math.cos(angle), math.sin(angle)
  local d = { v[1] - c[1], v[2] - c[2], v[3] - c[3] }
  local kd = k[1] * d[1] + k[2] * d[2] + k[3] * d[3]
  local cross = { k[2] * d[3] - k[3] * d[2], k[3] * d[1] - k[1] * d[3], k[1] * d[2] - k[2] * d[1] }
  local p = {}
  for a = 1, 3 do p[a] = c[a] + d[a] * cos + cross[a] * sin + k[a] * kd * (1 - cos) + distance * m.velocity[a] end
  return p
end

local function moved_vertices(s, motion, i, distance)
  local moved = {}
  for _, v in ipairs(s:block(i):vertices()) do moved[#moved + 1] = moved_point(s, motion, i, distance, v) end
  return moved
end

-- The vertices of each group ("g name") of an OBJ file, by name: the positions its faces use, once each.
local function obj_groups(text)
  local positions, groups, current = {}, {}, nil
  for line in text:gmatch("[^\n]+") do
    local x, y, z = line:match("^v%s+(%S+)%s+(%S+)%s+(%S+)")
    if x then positions[#positions + 1] = { tonumber(x), tonumber(y), tonumber(z) } end
    local name = line:match("^g%s+(.+)$")
    if name then current = { used = {} }; groups[name] = current end
    if line:match("^f%s") then
      for index in line:gmatch("%s(%d+)") do current.used[tonumber(index)] = true end
    end
  end
  for _, group in pairs(groups) do
    group.points = {}
    for index in pairs(group.used) do group.points[#group.points + 1] = positions[index] end
  end
  return groups
end

local function distance3(p, q)
  return math.sqrt((p[1] - q[1]) ^ 2 + (p[2] - q[2]) ^ 2 + (p[3] - q[3]) ^ 2)
end

local FREE_FILL, SUPPORT_FILL = "87%,86%,83%", "70%,69%,66%"

describe("limit interfaces", function()
  -- The arch of the load factor's golden value, tilted by atan(k * factor): a horizontal body force k * factor
  -- times each block's weight (ashlar.tilt).
  it("of ashlar.analyze past the load factor are the load factor's hinges, without the solver's noise", function()
    local n = 64
    local s = models.arch{ radius = 1, thickness = 0.15, voussoirs = n }
    local f = ashlar.load_factor(s, NO_SLIDING)
    near(f.factor, 0.14469729900464, 1e-9, "load factor")
    local hinges = { 9, 29, 50, 64 }
    assert.same(hinges, joints_of(f.limit, n))
    -- Just past the factor: the same four hinges, each a hinge (no slip at friction = math.huge).
    local r = ashlar.analyze(ashlar.tilt(s, math.atan(1.001 * f.factor)), NO_SLIDING)
    assert.is_false(r.stable)
    assert.same(hinges, joints_of(r.limit, n))
    for _, limit in ipairs(r.limit) do assert.equal("hinge", limit.mode) end
    -- At 1.02 times it the best equilibrium with tension opens a joint next to two of them too (opening
    -- rates 0.03 to 0.2 of the fastest block, not noise): every joint listed is a hinge within one joint of one
    -- of the four, and each of the four is listed.
    r = ashlar.analyze(ashlar.tilt(s, math.atan(1.02 * f.factor)), NO_SLIDING)
    local listed = joints_of(r.limit, n)
    assert.is_true(#listed <= 8)
    for _, limit in ipairs(r.limit) do
      assert.equal("hinge", limit.mode)
      local joint, nearest = joint_of(limit, n), math.huge
      for _, h in ipairs(hinges) do nearest = math.min(nearest, math.abs(joint - h)) end
      assert.is_true(nearest <= 1, "joint " .. joint)
    end
    for _, h in ipairs(hinges) do
      local found = false
      for _, j in ipairs(listed) do found = found or math.abs(j - h) <= 1 end
      assert.is_true(found, "hinge " .. h)
    end
  end)
end)

describe("ashlar.draw and ashlar.export of a load factor's result", function()
  local dir
  before_each(function() dir = support.temp_folder() end)
  after_each(function() support.remove_folder(dir) end)

  local n = 24
  local s = models.arch{ radius = 1, thickness = 0.15, voussoirs = n }
  local f = ashlar.load_factor(s, NO_SLIDING)

  it("has the four-hinge mechanism's hinges, each a rigid segment turning about them", function()
    local expected, hinges = four_hinge.collapse_factor(s, n)
    near(f.factor, expected, 1e-9 * expected, "factor")
    local joints = joints_of(f.limit, n)
    for k = 1, 4 do assert.equal(hinges[k][1], joints[k]) end
    -- The first segment (voussoirs 1..j2) turns about the first hinge's pivot: it stands still there.
    local pivot = f.limit[1].pivot
    for i = 1, joints[2] do
      local m, c = f.mechanism[i], s:block(i):centroid()
      local d = { pivot[1] - c[1], pivot[2] - c[2], pivot[3] - c[3] }
      local w = m.rotation
      local v = { m.velocity[1] + w[2] * d[3] - w[3] * d[2], m.velocity[2] + w[3] * d[1] - w[1] * d[3],
                  m.velocity[3] + w[1] * d[2] - w[2] * d[1] }
      near(math.sqrt(v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2), 0, 1e-6, "voussoir " .. i .. " at the first hinge")
    end
  end)

  it("marks the hinges at their pivots, on the line of thrust at the factor", function()
    local path = dir .. "/limit.svg"
    ashlar.draw(s, path, { result = f, thrust_color = { 1, 0, 0 } })
    local paths = svg_paths(support.read_file(path))
    local map = elevation_map(paths, { FREE_FILL, SUPPORT_FILL }, model_points(s))
    -- Hinge markers: black filled circles (arcs: C commands), their centre the middle of their extent.
    local markers = {}
    for _, p in ipairs(with_fill(paths, "0%,0%,0%")) do
      if p.d:find("C", 1, true) then
        local lo, hi = bounds(p.points)
        markers[#markers + 1] = { (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2 }
      end
    end
    assert.equal(4, #markers)
    local thrust = {}
    for _, p in ipairs(paths) do
      if p.style:find("stroke:rgb(100%,0%,0%)", 1, true) and p.style:find("fill:none", 1, true) then
        for _, q in ipairs(p.points) do thrust[#thrust + 1] = q end
      end
    end
    assert.is_true(#thrust > n)
    for k, limit in ipairs(f.limit) do
      local at = map(limit.pivot[1], limit.pivot[3])
      local nearest, on_thrust = math.huge, math.huge
      for _, m in ipairs(markers) do nearest = math.min(nearest, math.sqrt((m[1] - at[1]) ^ 2 + (m[2] - at[2]) ^ 2)) end
      for _, q in ipairs(thrust) do on_thrust = math.min(on_thrust, math.sqrt((q[1] - at[1]) ^ 2 + (q[2] - at[2]) ^ 2)) end
      -- Within a pixel (the image is about 300 px per metre).
      near(nearest, 0, 1.0, "marker of hinge " .. k)
      -- At the factor the centre of pressure of a hinge joint is at its pivot.
      near(on_thrust, 0, 1.0, "thrust line at hinge " .. k)
    end
    ashlar.draw(s, dir .. "/limit.png", { result = f, mechanism = 0.1 })
    assert.equal("\137PNG", support.read_file(dir .. "/limit.png"):sub(1, 4))
  end)

  it("draws the blocks moved by the mechanism, the fastest centroid by the given distance", function()
    local distance = 0.2
    local path = dir .. "/displaced.svg"
    ashlar.draw(s, path, { result = f, mechanism = distance, mechanism_color = { 0, 0, 1 } })
    -- The (x, z) of each voussoir's moved vertices.
    local displaced, all = {}, model_points(s)
    local fastest = 0
    for i = 1, n do
      local m = f.mechanism[i]
      fastest = math.max(fastest, math.sqrt(m.velocity[1] ^ 2 + m.velocity[2] ^ 2 + m.velocity[3] ^ 2))
      for _, p in ipairs(moved_vertices(s, f.mechanism, i, distance)) do
        displaced[#displaced + 1] = { p[1], p[3] }
        all[#all + 1] = { p[1], p[3] }
      end
    end
    near(fastest, 1, 1e-12, "the mechanism's fastest centroid")
    local paths = svg_paths(support.read_file(path))
    local outlines = {}
    for _, p in ipairs(paths) do
      if p.style:find("stroke:rgb(0%,0%,100%)", 1, true) and p.style:find("stroke-dasharray", 1, true) then
        outlines[#outlines + 1] = p
      end
    end
    assert.equal(n, #outlines)  -- one front face per voussoir
    -- The fit covers the blocks and their moved outlines: the map from metres to the image.
    local image = {}
    for _, rgb in ipairs{ FREE_FILL, SUPPORT_FILL } do
      for _, p in ipairs(with_fill(paths, rgb)) do for _, q in ipairs(p.points) do image[#image + 1] = q end end
    end
    for _, p in ipairs(outlines) do for _, q in ipairs(p.points) do image[#image + 1] = q end end
    local ilo, ihi = bounds(image)
    local mlo, mhi = bounds(all)
    local px = (ihi[1] - ilo[1]) / (mhi[1] - mlo[1])
    near((ihi[2] - ilo[2]) / (mhi[2] - mlo[2]), px, 1e-3 * px, "equal scales")
    local function map(p) return { ilo[1] + (p[1] - mlo[1]) * px, ilo[2] + (mhi[2] - p[2]) * px } end
    local original = {}
    for i = 1, n do
      for _, v in ipairs(s:block(i):vertices()) do original[#original + 1] = map{ v[1], v[3] } end
    end
    -- Every outline corner is a moved vertex, to within a pixel; some moved by about the distance.
    local moved = 0
    for _, p in ipairs(outlines) do
      for _, q in ipairs(p.points) do
        local from, nearest = math.huge, math.huge
        for _, o in ipairs(original) do from = math.min(from, math.sqrt((o[1] - q[1]) ^ 2 + (o[2] - q[2]) ^ 2)) end
        for _, d in ipairs(displaced) do
          local m = map(d)
          nearest = math.min(nearest, math.sqrt((m[1] - q[1]) ^ 2 + (m[2] - q[2]) ^ 2))
        end
        near(nearest, 0, 1.0, "outline corner")
        moved = math.max(moved, from)
      end
    end
    assert.is_true(moved > 0.5 * distance * px)
  end)

  it("exports the blocks moved by the mechanism and a rod at each hinge (OBJ)", function()
    local distance = 0.2
    local path = dir .. "/limit.obj"
    ashlar.export(s, path, { result = f, mechanism = distance })
    local groups = obj_groups(support.read_file(path))
    for i = 1, n do
      local group = groups[s:name(i)]
      local expected = moved_vertices(s, f.mechanism, i, distance)
      assert.equal(#expected, #group.points)
      for _, p in ipairs(group.points) do
        local nearest = math.huge
        for _, q in ipairs(expected) do nearest = math.min(nearest, distance3(p, q)) end
        near(nearest, 0, 1e-6, s:name(i))  -- OBJ keeps 6 significant digits
      end
    end
    -- The supports stay; the thrust line at the factor is drawn.
    for _, p in ipairs(groups["support left"].points) do
      local nearest = math.huge
      for _, q in ipairs(s:block(n + 1):vertices()) do nearest = math.min(nearest, distance3(p, q)) end
      near(nearest, 0, 1e-6, "support left")
    end
    assert.is_truthy(groups["thrust line"])
    -- A rod per hinge, centred on its pivot (the joints run the arch's whole depth, symmetric about y = 0),
    -- moved with the joint's free block (a, or b when a is a support).
    for _, limit in ipairs(f.limit) do
      local carrier = s:is_support(limit.a) and limit.b or limit.a
      local centre = moved_point(s, f.mechanism, carrier, distance, limit.pivot)
      local rod = groups[("hinge %d-%d"):format(limit.a, limit.b)]
      assert.is_truthy(rod, "hinge " .. limit.a .. "-" .. limit.b)
      local c = { 0, 0, 0 }
      for _, p in ipairs(rod.points) do for a = 1, 3 do c[a] = c[a] + p[a] / #rod.points end end
      near(distance3(c, centre), 0, 1e-5, "rod of hinge " .. limit.a .. "-" .. limit.b)
    end
    -- limit = false: no rods.
    ashlar.export(s, path, { result = f, limit = false })
    assert.is_nil(obj_groups(support.read_file(path))[("hinge %d-%d"):format(f.limit[1].a, f.limit[1].b)])
  end)

  it("marks an unstable kinematic analysis's hinges with limit = true, and none by default", function()
    -- t/R 0.09 is below the 24-voussoir minimum (0.1071): it falls without sliding.
    local thin = models.arch{ radius = 1, thickness = 0.09, voussoirs = n }
    local r = ashlar.analyze(thin, { friction = math.huge, method = "kinematic" })
    assert.is_false(r.stable)
    local hinges = 0
    for _, limit in ipairs(r.limit) do
      if limit.mode == "hinge" or limit.mode == "hinge_sliding" then hinges = hinges + 1 end
    end
    assert.is_true(hinges >= 4)
    local function dots(options)
      ashlar.draw(thin, dir .. "/kinematic.svg", options)
      local count = 0
      for _, p in ipairs(with_fill(svg_paths(support.read_file(dir .. "/kinematic.svg")), "0%,0%,0%")) do
        if p.d:find("C", 1, true) then count = count + 1 end
      end
      return count
    end
    assert.equal(hinges, dots{ result = r, limit = true, mechanism = 0.1 })
    assert.equal(0, dots{ result = r })
  end)

  it("reports bad mechanism options clearly", function()
    expect_error({ "mechanism needs a result with a mechanism" },
                 function() ashlar.draw(s, dir .. "/x.svg", { mechanism = 0.1 }) end)
    expect_error({ "mechanism", "-1" }, function() ashlar.draw(s, dir .. "/x.svg", { result = f, mechanism = -1 }) end)
    local damaged = { factor = f.factor, load = "body_force", direction = { 1, 0, 0 }, friction = math.huge,
                      mechanism = f.mechanism, limit = { { interface = 999, mode = "hinge", pivot = { 0, 0, 0 } } } }
    expect_error({ "limit interface 999 is not one of the structure's" },
                 function() ashlar.draw(s, dir .. "/x.svg", { result = damaged }) end)
    expect_error({ "a load factor of the kinematic method has no equilibrium at its factor" },
                 function() ashlar.draw(s, dir .. "/x.svg", { result = { factor = 0.1, method = "kinematic" } }) end)
    damaged.limit, damaged.friction = f.limit, "high"
    expect_error({ "result.friction: expected a number >= 0", "string" },
                 function() ashlar.draw(s, dir .. "/x.svg", { result = damaged }) end)
  end)
end)
