-- Joint geometry of models.arch, in the x-z plane. joints(o, fail) returns the n + 1 joints from the left springing
-- (joint 0) to the right one (joint n), each { ix, iz, ex, ez }: its
-- intrados and extrados points. Voussoir k lies between joints k - 1 and k;
-- voussoir(a, b, ...) builds it (the one block this file makes).
--
-- Every shape is symmetric about x = 0: the left half is computed and
-- mirrored, so the arch is exactly symmetric and, for an even count, the
-- crown joint lies exactly on x = 0 (the radial semicircle excepted: it keeps
-- the joint-by-joint construction it always had). The springing joints are horizontal
-- (z = 0, exactly): where the centreline meets the springing at an angle
-- (segmental, catenary), the springing joint is the cut of the arch ring by
-- the plane z = 0, so the first voussoir has a horizontal bottom face.
local shapes = {}

-- Cross product of (b - a) and (c - b) in the x-z plane.
local function turn(a, b, c)
  return (b[1] - a[1]) * (c[2] - b[2]) - (b[2] - a[2]) * (c[1] - b[1])
end

local function distance(a, b)
  return math.sqrt((b[1] - a[1]) ^ 2 + (b[2] - a[2]) ^ 2)
end

-- A voussoir's section (intrados and extrados chords between two joints)
-- must be a convex quadrilateral with some area. A corner is flat when the
-- sine of its turn is below 1e-12: relative to its edges, so the test holds
-- at any scale.
local function check_section(k, a, b, fail)
  local p = { { a.ix, a.iz }, { a.ex, a.ez }, { b.ex, b.ez }, { b.ix, b.iz } }
  local sign
  for i = 1, 4 do
    local q, r = p[i % 4 + 1], p[(i + 1) % 4 + 1]
    local t = turn(p[i], q, r)
    if math.abs(t) <= 1e-12 * distance(p[i], q) * distance(q, r) then sign = nil; break end
    if sign == nil then sign = t > 0 elseif sign ~= (t > 0) then sign = nil; break end
    if i == 4 then return end
  end
  fail(("voussoir %d is degenerate (its section is not a convex quadrilateral): change the number of voussoirs, "
    .. "the thickness or the joints"):format(k))
end

-- A left-half circle: centre (xc, zc), centreline radius r, joint k of the
-- half's m at angle theta(k); the centreline meets z = 0 at the left
-- springing. Vertical joints pass through the centreline points.
local function circle(o, xc, zc, r, theta, m, crown, fail)
  local ri, ro = r - o.thickness / 2, r + o.thickness / 2
  local function on(radius, x) -- height of the circle of `radius` above x, or nil
    local h = radius * radius - (x - xc) ^ 2
    if h <= 0 then return nil end
    return zc + math.sqrt(h)
  end
  return function(k)
    if k == 0 then
      -- Where the intrados and extrados circles cross z = 0.
      return { ix = xc - math.sqrt(ri * ri - zc * zc), iz = 0, ex = xc - math.sqrt(ro * ro - zc * zc), ez = 0 }
    end
    if k == m and crown then return crown end
    local c, s = math.cos(theta(k)), math.sin(theta(k))
    if o.joints == "radial" then
      return { ix = xc + ri * c, iz = zc + ri * s, ex = xc + ro * c, ez = zc + ro * s }
    end
    local x = k == m and 0 or xc + r * c
    local iz, ez = on(ri, x), on(ro, x)
    if not iz or iz <= 0 then
      fail(("joints = \"vertical\": joint %d at x = %g misses the intrados (which springs at x = %g); "
        .. "use fewer voussoirs, a thinner arch or radial joints"):format(k, x, xc - math.sqrt(ri * ri - zc * zc)))
    end
    return { ix = x, iz = iz, ex = x, ez = ez }
  end
end

-- The left half's joint k (0 <= k <= n / 2) of each shape.
local half = {}

function half.semicircular(o, fail)
  local n = o.voussoirs
  return circle(o, 0, 0, o.radius, function(k) return math.pi * (1 - k / n) end, n / 2, nil, fail)
end

function half.pointed(o, fail)
  local m, e, r = o.voussoirs // 2, o.eccentricity, o.radius
  local apex = math.acos(-e) -- centreline angle of the apex, about the left half's centre (e r, 0)
  local ri, ro = r - o.thickness / 2, r + o.thickness / 2
  -- The halves meet at a vertical joint on x = 0.
  local crown = { ix = 0, iz = math.sqrt(ri * ri - e * e * r * r), ex = 0, ez = math.sqrt(ro * ro - e * e * r * r) }
  return circle(o, e * r, 0, r, function(k) return math.pi - k * (math.pi - apex) / m end, m, crown, fail)
end

function half.segmental(o, fail)
  local n, f = o.voussoirs, o.rise
  local r = (o.span ^ 2 / 4 + f * f) / (2 * f)
  local zc = f - r
  -- The radial joints divide the arc between the angles where the intrados
  -- meets the springing plane, so that joint 1 stands above it however
  -- many voussoirs there are (the first voussoir also holds the wedge of
  -- ring outside that angle, down to the horizontal springing joint).
  local ri = r - o.thickness / 2
  local springing = math.atan(-zc, -math.sqrt(ri * ri - zc * zc))
  return circle(o, 0, zc, r, function(k) return springing - k * (springing - math.pi / 2) / (n / 2) end,
    n / 2, nil, fail)
end

-- Joints normal to the centreline through centreline points c at equal arc
-- lengths; point(s) gives the centreline point and outward unit normal at
-- arc length s from the left springing.
local function normal_joints(o, point, springing)
  local t = o.thickness / 2
  return function(k)
    if k == 0 and springing then return springing end
    local x, z, nx, nz = point(k)
    return { ix = x - t * nx, iz = z - t * nz, ex = x + t * nx, ez = z + t * nz }
  end
end

function half.elliptical(o)
  local a, b, n = o.span / 2, o.rise, o.voussoirs
  -- Arc length along theta from pi (left springing) to pi / 2 (crown), by
  -- the trapezoid rule on a fine table, inverted by interpolation.
  local steps = 4096
  local function speed(theta) return math.sqrt((a * math.sin(theta)) ^ 2 + (b * math.cos(theta)) ^ 2) end
  local length = { [0] = 0 }
  for i = 1, steps do
    local t0, t1 = math.pi - (i - 1) * (math.pi / 2) / steps, math.pi - i * (math.pi / 2) / steps
    length[i] = length[i - 1] + (speed(t0) + speed(t1)) / 2 * (math.pi / 2) / steps
  end
  local function theta_at(s)
    local lo, hi = 0, steps
    while hi - lo > 1 do
      local mid = (lo + hi) // 2
      if length[mid] <= s then lo = mid else hi = mid end
    end
    local w = (s - length[lo]) / (length[hi] - length[lo])
    return math.pi - (lo + w) * (math.pi / 2) / steps
  end
  return normal_joints(o, function(k)
    local theta = k == 0 and math.pi or theta_at(k * 2 * length[steps] / n)
    local c, s = math.cos(theta), math.sin(theta)
    if k == 0 then c, s = -1, 0 end
    local nx, nz = c / a, s / b
    local norm = math.sqrt(nx * nx + nz * nz)
    return a * c, b * s, nx / norm, nz / norm
  end)
end

-- Catenary parameter a with a (cosh(span / 2a) - 1) = rise, by bisection
-- (the left side falls from infinity to 0 as a grows).
function shapes.catenary_parameter(span, rise)
  local function excess(a) return a * (math.cosh(span / (2 * a)) - 1) - rise end
  local lo, hi = span / 2, span / 2
  while excess(lo) < 0 do lo = lo / 2 end
  while excess(hi) > 0 do hi = hi * 2 end
  for _ = 1, 200 do
    local mid = (lo + hi) / 2
    if excess(mid) > 0 then lo = mid else hi = mid end
  end
  return (lo + hi) / 2
end

function half.catenary(o)
  local f, n, t = o.rise, o.voussoirs, o.thickness / 2
  local a = shapes.catenary_parameter(o.span, f)
  local function z(x) return f + a - a * math.cosh(x / a) end
  -- Offset (side -1 intrados, +1 extrados) of the centreline point above x.
  local function offset(x, side)
    return x + side * t * math.tanh(x / a), z(x) + side * t / math.cosh(x / a)
  end
  -- The offset point on z = 0 (lo below it, hi above) and its centreline x.
  local function crossing(side, lo, hi)
    for _ = 1, 200 do
      local mid = (lo + hi) / 2
      if select(2, offset(mid, side)) < 0 then lo = mid else hi = mid end
    end
    return (offset((lo + hi) / 2, side)), (lo + hi) / 2
  end
  local outer = -o.span / 2
  while select(2, offset(outer, 1)) >= 0 do outer = outer - o.span / 2 end
  local ix, start = crossing(-1, -o.span / 2, 0)
  local springing = { ix = ix, iz = 0, ex = crossing(1, outer, -o.span / 2), ez = 0 }
  -- Equal arc lengths between the centreline points whose joints end on the
  -- springing plane at the intrados, so that joint 1 stands above it
  -- however many voussoirs there are.
  local half_length = -a * math.sinh(start / a)
  return normal_joints(o, function(k)
    local y = (half_length - k * 2 * half_length / n) / a -- >= 0 on the left half
    local x = -a * math.log(y + math.sqrt(y * y + 1))     -- a asinh(-y)
    local sh, ch = math.sinh(x / a), math.cosh(x / a)
    return x, z(x), sh / ch, 1 / ch
  end, springing)
end

-- The voussoir between joints a and b, the joints moved by (x, z), as the
-- solid between the two joint rectangles from y = y0 to y1.
function shapes.voussoir(a, b, x, z, y0, y1, density)
  local function rectangle(j)
    return { { x + j.ix, y0, z + j.iz }, { x + j.ex, y0, z + j.ez }, { x + j.ex, y1, z + j.ez }, { x + j.ix, y1, z + j.iz } }
  end
  return require("ashlar").loft(rectangle(a), rectangle(b), { density = density })
end

function shapes.joints(o, fail)
  local n = o.voussoirs
  local left = half[o.shape](o, fail)
  local joints = {}
  if o.shape == "semicircular" and o.joints == "radial" then
    -- Computed joint by joint, not mirrored, as models.arch always has: the
    -- same vertices, bit for bit (symmetric to rounding).
    for k = 0, n - 1 do joints[k] = left(k) end
    joints[n] = { ix = -joints[0].ix, iz = 0, ex = -joints[0].ex, ez = 0 }
    for k = 1, n do check_section(k, joints[k - 1], joints[k], fail) end
    return joints
  end
  for k = 0, n // 2 do
    local j = left(k)
    if 2 * k == n then j.ix, j.ex = 0, 0 end
    joints[k] = j
  end
  for k = n // 2 + 1, n do
    local j = joints[n - k]
    joints[k] = { ix = -j.ix, iz = j.iz, ex = -j.ex, ez = j.ez }
  end
  for k = 1, n do check_section(k, joints[k - 1], joints[k], fail) end
  return joints
end

return shapes
