-- models.dome: a spherical dome of voussoirs on a ring of support blocks.
--
-- The sphere is centred at the origin, z up; `radius` is the radius of the
-- mid-surface and the shell runs from radius - thickness/2 (intrados) to
-- radius + thickness/2 (extrados). Positions on it are given by the polar
-- angle phi from the apex (+z) and the azimuth theta from +x.
--
-- Courses (parallels) are bounded by radial, i.e. conical, bed joints
-- through the sphere's centre; voussoirs within a course by meridian planes
-- through the z axis. Every face is planar: a voussoir's corners are points
-- of the intrados and extrados on two meridians and two parallels, so its
-- meridian faces lie in meridian planes, its bed faces (points r d(phi,
-- theta1), r d(phi, theta2) for two radii r) in planes through the origin,
-- and its intrados and extrados are isosceles trapezoids (planar chords of
-- the sphere). Each face is a planar facet of a polyhedral cone or sphere,
-- so a voussoir is (extrados pyramid from the origin) - (intrados pyramid).
--
-- Staggered bond turns every second course (counted from the bottom) by
-- half a meridian step. Its bed joints would then meet facets of another
-- plane, so in that bond every voussoir is built on the finer grid of
-- 2 * meridians half steps: each face is split at the voussoir's middle
-- meridian into two planar facets (12 corners per voussoir, not convex), and
-- the facets of two courses coincide exactly, half a voussoir each.
--
-- The top: with `oculus` (polar angle of the opening) the top course ends
-- there, open. Without it a single keystone closes the dome: a pyramidal
-- shell from the apex down to the top course, its bed a ring of conical
-- facets matching the course below.
--
-- The bottom: a hemisphere springs at z = 0 (horizontal bed). A spherical
-- cap (`cap` = polar angle of its lowest bed joint, < pi/2) keeps the
-- conical bed joint there, so its springing is not horizontal. Under every
-- facet of the lowest bed joint sits a support block: that facet extruded
-- thickness downwards (along -z), so its top is exactly the facet and the
-- contact is found in full. Neighbouring supports touch along meridian
-- planes; supports carry no equilibrium equations, so that is harmless.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local half_pi = math.pi / 2

local spec = {
  radius = { type = "number", default = 5, above = 0 },          -- m, of the mid-surface
  thickness = { type = "number", default = 0.5, above = 0 },     -- m, radial
  meridians = { type = "number", default = 16, integer = true, min = 3 },
  -- The minimum thickness stays within 1% of its value at 64 from 18
  -- parallels on (scripts/model_discretisation.lua).
  parallels = { type = "number", default = 18, integer = true, min = 1 },  -- courses of voussoirs
  oculus = { type = "number", above = 0 },                       -- rad from the apex; nil: keystone
  cap = { type = "number", above = 0, max = half_pi },           -- rad from the apex; nil: hemisphere
  bond = { type = "string", default = "stacked", one_of = { "stacked", "staggered" } },
  density = { type = "number", default = 2400, above = 0 },      -- kg/m^3
}

-- Unit vector at polar angle phi and azimuth index j of `steps` around the
-- circle. The springing and the apex, and the azimuths, are set exactly so
-- that the springing is horizontal and the wrap-around vertices coincide.
local function direction(phi, j, steps)
  local sin_phi, cos_phi
  if phi == half_pi then sin_phi, cos_phi = 1, 0
  elseif phi == 0 then sin_phi, cos_phi = 0, 1
  else sin_phi, cos_phi = math.sin(phi), math.cos(phi) end
  j = j % steps
  local theta = 2 * math.pi * j / steps
  local c, s = math.cos(theta), math.sin(theta)
  if 4 * j == steps then c, s = 0, 1
  elseif 2 * j == steps then c, s = -1, 0
  elseif 4 * j == 3 * steps then c, s = 0, -1
  elseif j == 0 then c, s = 1, 0 end
  return { sin_phi * c, sin_phi * s, cos_phi }
end

local function scaled(r, d) return { r * d[1], r * d[2], r * d[3] } end

-- Orders a face loop counter-clockwise seen from outside: its Newell normal
-- must point along `outward` (a direction known to leave the block there).
local function oriented(vertices, loop, outward)
  local n = { 0, 0, 0 }
  for k = 1, #loop do
    local p, q = vertices[loop[k]], vertices[loop[k % #loop + 1]]
    n[1] = n[1] + (p[2] - q[2]) * (p[3] + q[3])
    n[2] = n[2] + (p[3] - q[3]) * (p[1] + q[1])
    n[3] = n[3] + (p[1] - q[1]) * (p[2] + q[2])
  end
  if n[1] * outward[1] + n[2] * outward[2] + n[3] * outward[3] < 0 then
    local reversed = {}
    for k = #loop, 1, -1 do reversed[#reversed + 1] = loop[k] end
    return reversed
  end
  return loop
end

local function mean(points)
  local c = { 0, 0, 0 }
  for _, p in ipairs(points) do for i = 1, 3 do c[i] = c[i] + p[i] / #points end end
  return c
end

-- The voussoir between polar angles top < bottom over the azimuth indices
-- js (consecutive, of `steps`): two or three of them, one planar facet of
-- each face between consecutive ones.
local function voussoir(inner, outer, top, bottom, js, steps, density)
  local vertices, faces = {}, {}
  local ib, ob, it, ot = {}, {}, {}, {}
  for k, j in ipairs(js) do
    local db, dt = direction(bottom, j, steps), direction(top, j, steps)
    vertices[#vertices + 1] = scaled(inner, db); ib[k] = #vertices
    vertices[#vertices + 1] = scaled(outer, db); ob[k] = #vertices
    vertices[#vertices + 1] = scaled(inner, dt); it[k] = #vertices
    vertices[#vertices + 1] = scaled(outer, dt); ot[k] = #vertices
  end
  local function add(loop, outward) faces[#faces + 1] = oriented(vertices, loop, outward) end
  for k = 1, #js - 1 do
    local mid = mean{ vertices[ib[k]], vertices[ib[k + 1]], vertices[it[k]], vertices[it[k + 1]] }
    local up = mean{ vertices[ot[k]], vertices[ot[k + 1]] }       -- on the top bed, outwards
    local down = mean{ vertices[ob[k]], vertices[ob[k + 1]] }
    add({ ib[k], ib[k + 1], it[k + 1], it[k] }, { -mid[1], -mid[2], -mid[3] })   -- intrados
    add({ ob[k], ob[k + 1], ot[k + 1], ot[k] }, mid)                             -- extrados
    add({ it[k], it[k + 1], ot[k + 1], ot[k] }, { up[1] - down[1], up[2] - down[2], up[3] - down[3] })
    add({ ib[k], ib[k + 1], ob[k + 1], ob[k] }, { down[1] - up[1], down[2] - up[2], down[3] - up[3] })
  end
  -- Meridian faces: outwards is away from the voussoir's other corners.
  local centre = mean(vertices)
  for _, k in ipairs{ 1, #js } do
    local p = vertices[ob[k]]
    local tangent = { -p[2], p[1], 0 }                 -- increasing azimuth at p
    local sign = (centre[1] - p[1]) * tangent[1] + (centre[2] - p[2]) * tangent[2] > 0 and -1 or 1
    add({ ib[k], ob[k], ot[k], it[k] }, { sign * tangent[1], sign * tangent[2], 0 })
  end
  return ashlar.block{ vertices = vertices, faces = faces, density = density }
end

-- The keystone: a pyramidal shell from the apex down to polar angle
-- `bottom`, with one bed facet per azimuth step (steps of `stride` on the
-- grid of `steps`).
local function keystone(inner, outer, bottom, steps, stride, density)
  local vertices = { { 0, 0, inner }, { 0, 0, outer } }
  local ib, ob = {}, {}
  for j = 0, steps - 1, stride do
    local d = direction(bottom, j, steps)
    vertices[#vertices + 1] = scaled(inner, d); ib[#ib + 1] = #vertices
    vertices[#vertices + 1] = scaled(outer, d); ob[#ob + 1] = #vertices
  end
  local faces = {}
  local function add(loop, outward) faces[#faces + 1] = oriented(vertices, loop, outward) end
  for k = 1, #ib do
    local l = k % #ib + 1
    local mid = mean{ vertices[ob[k]], vertices[ob[l]] }
    add({ 2, ob[k], ob[l] }, mid)                                          -- extrados
    add({ 1, ib[k], ib[l] }, { -mid[1], -mid[2], -mid[3] })                -- intrados
    -- Bed facet: outwards is down the meridian, away from the apex.
    add({ ib[k], ib[l], ob[l], ob[k] }, { mid[1], mid[2], mid[3] - outer })
  end
  return ashlar.block{ vertices = vertices, faces = faces, density = density }
end

return function(opts)
  local o = options.check("models.dome", opts, spec)
  options.limit_blocks("models.dome", o.meridians * o.parallels,
    ("meridians x parallels = %d x %d"):format(o.meridians, o.parallels))
  if o.thickness >= 2 * o.radius then
    error(("models.dome: thickness must be < 2 * radius (%g), got %g"):format(2 * o.radius,
      o.thickness), 2)
  end
  local bottom = o.cap or half_pi
  if o.oculus and o.oculus >= bottom then
    error(("models.dome: oculus must be < %s (%g), got %g"):format(o.cap and "cap" or "pi/2",
      bottom, o.oculus), 2)
  end
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local n, p = o.meridians, o.parallels
  local staggered = o.bond == "staggered"
  local steps = 2 * n                                   -- the half-step azimuth grid
  -- Bed joint angles from the bottom (k = 0) up; without an oculus one more
  -- step is left above the top course for the keystone.
  local top = o.oculus or 0
  local divisions = o.oculus and p or p + 1
  local function bed(k)
    if k == 0 then return bottom end
    if k == divisions then return top end
    return bottom - k * (bottom - top) / divisions
  end

  local s = ashlar.structure()
  for c = 1, p do
    local shift = (staggered and c % 2 == 0) and 1 or 0
    for m = 1, n do
      local j0 = 2 * (m - 1) + shift
      local js = staggered and { j0, j0 + 1, j0 + 2 } or { j0, j0 + 2 }
      s:add(voussoir(inner, outer, bed(c), bed(c - 1), js, steps, o.density),
            { name = ("course %d block %d"):format(c, m) })
    end
  end
  if not o.oculus then
    s:add(keystone(inner, outer, bed(p), steps, staggered and 1 or 2, o.density), { name = "keystone" })
  end
  -- One support per facet of the lowest bed joint (course 1 is not shifted).
  local stride = staggered and 1 or 2
  local drop = { 0, 0, -o.thickness }
  for j = 0, steps - 1, stride do
    local a, b = direction(bottom, j, steps), direction(bottom, j + stride, steps)
    local facet = { scaled(inner, a), scaled(inner, b), scaled(outer, b), scaled(outer, a) }
    s:add(ashlar.prism(facet, drop, { density = o.density }),
          { support = true, name = ("support %d"):format(j // stride + 1) })
  end
  return s
end
