-- models.arch's shapes (semicircular, pointed, segmental, elliptical,
-- catenary) and joints (radial, vertical): topology, joint geometry against
-- the curves, exact polyhedral volumes, symmetry, option errors, and
-- equilibrium of pointed and segmental arches.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

-- Catenary parameter a with a (cosh(span / 2a) - 1) = rise, by bisection.
local function catenary_parameter(span, rise)
  local lo, hi = 1e-3, 1e3
  for _ = 1, 200 do
    local a = (lo + hi) / 2
    if a * (math.cosh(span / (2 * a)) - 1) > rise then lo = a else hi = a end
  end
  return (lo + hi) / 2
end

-- Each case: the options, and the centreline as residual(x, z) and normal(x, z)
-- (any length), or for a circular shape the centre of the circle through x.
local R, t, depth = 5, 0.4, 1.2
local span, rise = 8, 2
local a_cat = catenary_parameter(span, rise)
local seg_radius = (span ^ 2 / 4 + rise ^ 2) / (2 * rise)
local cases = {
  { name = "semicircular", opts = { shape = "semicircular", radius = R, thickness = t, voussoirs = 15 },
    centre = function() return 0, 0 end, radius = R },
  { name = "pointed", opts = { shape = "pointed", radius = R, eccentricity = 0.2, thickness = t, voussoirs = 16 },
    centre = function(x) return x < 0 and 0.2 * R or -0.2 * R, 0 end, radius = R, apex = true },
  { name = "segmental", opts = { shape = "segmental", span = span, rise = rise, thickness = t, voussoirs = 15 },
    centre = function() return 0, rise - seg_radius end, radius = seg_radius },
  { name = "elliptical", opts = { shape = "elliptical", span = span, rise = 3, thickness = t, voussoirs = 15 },
    residual = function(x, z) return (x / 4) ^ 2 + (z / 3) ^ 2 - 1 end,
    normal = function(x, z) return x / 16, z / 9 end },
  { name = "catenary", opts = { shape = "catenary", span = span, rise = rise, thickness = t, voussoirs = 16 },
    residual = function(x, z) return z - (rise + a_cat - a_cat * math.cosh(x / a_cat)) end,
    normal = function(x) return math.sinh(x / a_cat), 1 end },
  { name = "semicircular, vertical joints",
    opts = { shape = "semicircular", radius = R, thickness = t, voussoirs = 8, joints = "vertical" },
    centre = function() return 0, 0 end, radius = R, vertical = true },
  { name = "pointed, vertical joints",
    opts = { shape = "pointed", radius = R, eccentricity = 0.2, thickness = t, voussoirs = 8, joints = "vertical" },
    centre = function(x) return x < 0 and 0.2 * R or -0.2 * R, 0 end, radius = R, vertical = true, apex = true },
  { name = "segmental, vertical joints",
    opts = { shape = "segmental", span = span, rise = rise, thickness = t, voussoirs = 15, joints = "vertical" },
    centre = function() return 0, rise - seg_radius end, radius = seg_radius, vertical = true },
}

-- Joint k (0 = left springing) as intrados and extrados points in x-z,
-- from the interface between its two blocks.
local function joints(s, n)
  local found = {}
  for _, f in ipairs(s:interfaces()) do
    local k
    if f.b == f.a + 1 and f.b <= n then k = f.a
    elseif f.a == 1 and f.b == s:find("support left") then k = 0
    elseif f.a == n and f.b == s:find("support right") then k = n end
    assert(k and not found[k], ("spurious interface %d-%d"):format(f.a, f.b))
    local p, q = f.vertices[1], nil
    for _, v in ipairs(f.vertices) do
      if math.abs(v[1] - p[1]) + math.abs(v[3] - p[3]) > 1e-9 then q = v end
    end
    -- The extrados end is the higher one, or on a springing the outer one.
    local outer = q[3] > p[3] + 1e-12 or (math.abs(q[3] - p[3]) <= 1e-12 and math.abs(q[1]) > math.abs(p[1]))
    if outer then p, q = q, p end
    found[k] = { i = { q[1], q[3] }, e = { p[1], p[3] } }
  end
  for k = 0, n do assert(found[k], "missing joint " .. k) end
  return found
end

-- Area of the section between the extrados and intrados chords (shoelace).
local function section_area(j, n)
  local outline = {}
  for k = 0, n do outline[#outline + 1] = j[k].e end
  for k = n, 0, -1 do outline[#outline + 1] = j[k].i end
  local area = 0
  for i = 1, #outline do
    local p, q = outline[i], outline[i % #outline + 1]
    area = area + p[1] * q[2] - q[1] * p[2]
  end
  return math.abs(area) / 2
end

local function voussoir_volume(s, n)
  local volume = 0
  for i = 1, n do volume = volume + s:block(i):volume() end
  return volume
end

for _, case in ipairs(cases) do
  case.opts.depth = depth
  describe("models.arch " .. case.name, function()
    local s = models.arch(case.opts)
    local n = case.opts.voussoirs

    it("has N voussoirs named left to right, then the two supports", function()
      assert.equal(n + 2, #s)
      for i = 1, n do
        assert.equal(("voussoir %d"):format(i), s:name(i))
        assert.is_false(s:is_support(i))
        if i > 1 then assert.is_true(s:block(i):centroid()[1] > s:block(i - 1):centroid()[1]) end
      end
      assert.equal(n + 1, s:find("support left")); assert.equal(n + 2, s:find("support right"))
      assert.is_true(s:is_support(n + 1) and s:is_support(n + 2))
    end)

    it("has exactly the N + 1 joints, horizontal springings on the supports' tops", function()
      assert.equal(n + 1, #s:interfaces())
      local j = joints(s, n)
      for _, k in ipairs{ 0, n } do
        assert.equal(0, j[k].i[2]); assert.equal(0, j[k].e[2])
      end
      for _, f in ipairs(s:interfaces()) do
        if f.b > n then near(math.abs(f.normal[3]), 1, 1e-15, "springing normal") end
        near(f.area, depth * math.sqrt((f.vertices[1][1] - f.vertices[3][1]) ^ 2
          + (f.vertices[1][3] - f.vertices[3][3]) ^ 2) , 1e-9, "joint rectangle")
      end
    end)

    it("puts every joint on the shape's intrados and extrados", function()
      local j = joints(s, n)
      for k = 1, n - 1 do
        local i, e = j[k].i, j[k].e
        local mx, mz = (i[1] + e[1]) / 2, (i[2] + e[2]) / 2
        local dx, dz = e[1] - i[1], e[2] - i[2]
        local length = math.sqrt(dx * dx + dz * dz)
        if case.apex and 2 * k == n then
          near(i[1], 0, 0); near(e[1], 0, 0)  -- the vertical joint at the apex
          local cx = 0.2 * R
          near(math.sqrt(cx * cx + i[2] ^ 2), R - t / 2, 1e-12); near(math.sqrt(cx * cx + e[2] ^ 2), R + t / 2, 1e-12)
        elseif case.vertical then
          near(dx, 0, 1e-15, "vertical joint")
          local cx, cz = case.centre(mx)
          near(math.sqrt((i[1] - cx) ^ 2 + (i[2] - cz) ^ 2), case.radius - t / 2, 1e-12, "intrados")
          near(math.sqrt((e[1] - cx) ^ 2 + (e[2] - cz) ^ 2), case.radius + t / 2, 1e-12, "extrados")
        elseif case.centre then
          local cx, cz = case.centre(mx)
          near(length, t, 1e-12, "joint length")
          near(math.sqrt((mx - cx) ^ 2 + (mz - cz) ^ 2), case.radius, 1e-12, "centreline")
          near((mx - cx) * dz - (mz - cz) * dx, 0, 1e-12, "radial joint")
        else
          near(length, t, 1e-12, "joint length")
          near(case.residual(mx, mz), 0, 1e-12, "centreline")
          local nx, nz = case.normal(mx, mz)
          near((nx * dz - nz * dx) / math.sqrt(nx * nx + nz * nz), 0, 1e-12, "joint normal to the centreline")
        end
      end
    end)

    it("has the volume of the section between its chords", function()
      local expected = section_area(joints(s, n), n) * depth
      near(voussoir_volume(s, n), expected, 1e-12 * expected)
    end)

    it("is symmetric about x = 0", function()
      for i = 1, n do
        local c, mirror = s:block(i):centroid(), s:block(n + 1 - i):centroid()
        near(c[1], -mirror[1], 1e-12); near(c[3], mirror[3], 1e-12); near(c[2], 0, 1e-15)
        near(s:block(i):volume(), s:block(n + 1 - i):volume(), 1e-12)
      end
    end)
  end)
end

describe("models.arch closed forms", function()
  it("gives the semicircle's and the pointed arch's polyhedral volumes", function()
    local ri, ro = R - t / 2, R + t / 2
    local s = models.arch{ radius = R, thickness = t, voussoirs = 15, depth = depth }
    local expected = 15 * 0.5 * (ro ^ 2 - ri ^ 2) * math.sin(math.pi / 15) * depth
    near(voussoir_volume(s, 15), expected, 1e-12 * expected)
    -- Pointed: per half, m - 1 annulus trapezoids and one quadrilateral
    -- against the vertical joint at the apex.
    local e, m = 0.2, 8
    local apex = math.acos(-e)
    local step = (math.pi - apex) / m
    local last = math.pi - (m - 1) * step
    local quad = { { e * R + ri * math.cos(last), ri * math.sin(last) }, { e * R + ro * math.cos(last), ro * math.sin(last) },
                   { 0, math.sqrt(ro ^ 2 - (e * R) ^ 2) }, { 0, math.sqrt(ri ^ 2 - (e * R) ^ 2) } }
    local area = 0
    for i = 1, 4 do
      local p, q = quad[i], quad[i % 4 + 1]
      area = area + p[1] * q[2] - q[1] * p[2]
    end
    local half = (m - 1) * 0.5 * (ro ^ 2 - ri ^ 2) * math.sin(step) + math.abs(area) / 2
    local p = models.arch{ shape = "pointed", radius = R, eccentricity = e, thickness = t, voussoirs = 2 * m, depth = depth }
    near(voussoir_volume(p, 2 * m), 2 * half * depth, 1e-12 * half)
    -- Span 2 R (1 - e) between the centreline springings.
    local j = joints(p, 2 * m)
    near((j[0].i[1] + j[0].e[1]) / 2, -R * (1 - e), 1e-12)
  end)

  it("makes a pointed arch of eccentricity 0 the semicircle", function()
    for _, joints_kind in ipairs{ "radial", "vertical" } do
      local o = { radius = R, thickness = t, voussoirs = 8, joints = joints_kind }
      local semi = models.arch(o)
      o.shape, o.eccentricity = "pointed", 0
      local pointed = models.arch(o)
      assert.equal(#semi, #pointed)
      for i = 1, #semi do
        local a, b = semi:block(i):vertices(), pointed:block(i):vertices()
        assert.equal(#a, #b)
        for v = 1, #a do
          for c = 1, 3 do near(b[v][c], a[v][c], 1e-12, ("block %d vertex %d"):format(i, v)) end
        end
      end
    end
  end)

  it("keeps the first voussoir whole however fine the division (horizontal springing)", function()
    for _, shape in ipairs{ "segmental", "catenary" } do
      for _, n in ipairs{ 2, 3, 64, 512 } do
        local a = models.arch{ shape = shape, span = 10, rise = 2.5, thickness = 1.5, voussoirs = n }
        assert.equal(n + 1, #a:interfaces(), shape .. " " .. n)
      end
    end
  end)

  it("accepts span instead of radius", function()
    local a = models.arch{ shape = "pointed", span = 8, eccentricity = 0.2, voussoirs = 8 }
    local b = models.arch{ shape = "pointed", radius = 5, eccentricity = 0.2, voussoirs = 8 }
    near(a:block(1):volume(), b:block(1):volume(), 1e-12)
    near(models.arch{ span = 10 }:block(3):volume(), models.arch{}:block(3):volume(), 1e-12)
  end)
end)

describe("models.arch abutments", function()
  local n, height, width = 15, 3, 1.5
  local s = models.arch{ shape = "segmental", span = span, rise = rise, thickness = t, voussoirs = n, depth = depth,
                         abutments = { width = width, height = height } }

  it("puts an abutment under each springing, on a support", function()
    assert.equal(n + 4, #s)
    assert.equal(n + 1, s:find("abutment left")); assert.equal(n + 2, s:find("abutment right"))
    assert.equal(n + 3, s:find("support left")); assert.equal(n + 4, s:find("support right"))
    assert.is_false(s:is_support(n + 1) or s:is_support(n + 2))
    assert.is_true(s:is_support(n + 3) and s:is_support(n + 4))
    local pairs_found = {}
    for _, f in ipairs(s:interfaces()) do pairs_found[#pairs_found + 1] = f.a .. "-" .. f.b end
    table.sort(pairs_found)
    local expected = { "1-" .. n + 1, n .. "-" .. n + 2, n + 1 .. "-" .. n + 3, n + 2 .. "-" .. n + 4 }
    for i = 1, n - 1 do expected[#expected + 1] = i .. "-" .. i + 1 end
    table.sort(expected)
    assert.same(expected, pairs_found)
    for _, name in ipairs{ "abutment left", "abutment right" } do
      near(s:block(name):volume(), width * height * depth, 1e-12)
    end
    near(s:block("abutment left"):centroid()[1], -s:block("abutment right"):centroid()[1], 1e-12)
    near(s:block("abutment left"):centroid()[3], -height / 2, 1e-12)
  end)

  it("stand on wide piers and tip over on slender ones", function()
    local function stable(w)
      local a = models.arch{ shape = "segmental", span = span, rise = rise, thickness = t, voussoirs = n,
                             abutments = { width = w, height = height } }
      return ashlar.analyze(a, { friction = math.huge }).stable
    end
    assert.is_true(stable(3)); assert.is_false(stable(0.6))
  end)

  it("rejects bad abutment options", function()
    expect_error({ "models.arch: abutments: unknown option 'depth' (allowed: height, width)" }, models.arch,
      { abutments = { depth = 1 } })
    expect_error({ "models.arch: abutments: height: must be > 0, got 0" }, models.arch, { abutments = { height = 0 } })
    expect_error({ "models.arch: abutments: expected a table, got number" }, models.arch, { abutments = 2 })
    expect_error({ "models.arch: abutments: width must be >= the springing joint's length (0.6), got 0.5" },
      models.arch, { abutments = { width = 0.5 } })
  end)
end)

describe("models.arch options", function()
  it("rejects bad options, naming models.arch", function()
    expect_error({ "models.arch: shape: 'gothic' is not one of semicircular, pointed, segmental, elliptical, catenary" },
      models.arch, { shape = "gothic" })
    expect_error({ "models.arch: joints: 'skew' is not one of radial, vertical" }, models.arch, { joints = "skew" })
    expect_error({ "models.arch: give radius or span, not both" }, models.arch, { radius = 5, span = 10 })
    expect_error({ "models.arch: rise: not an option of a semicircular arch" }, models.arch, { rise = 2 })
    expect_error({ "models.arch: eccentricity: not an option of a segmental arch" }, models.arch,
      { shape = "segmental", eccentricity = 0.1 })
    expect_error({ "models.arch: radius: not an option of a catenary arch" }, models.arch,
      { shape = "catenary", radius = 5 })
    expect_error({ "models.arch: eccentricity: must be < 1, got 1" }, models.arch, { shape = "pointed", eccentricity = 1 })
    expect_error({ "models.arch: eccentricity: must be >= 0, got -0.1" }, models.arch,
      { shape = "pointed", eccentricity = -0.1 })
    expect_error({ "models.arch: voussoirs: a pointed arch needs an even count", "got 15" }, models.arch,
      { shape = "pointed", voussoirs = 15 })
    expect_error({ "models.arch: thickness must be < span = 2 * radius * (1 - eccentricity) (4), got 4" }, models.arch,
      { shape = "pointed", radius = 5, eccentricity = 0.6, thickness = 4 })
    expect_error({ "models.arch: rise: a segmental arch needs rise < span / 2 (5), got 5" }, models.arch,
      { shape = "segmental", span = 10, rise = 5 })
    expect_error({ "models.arch: rise: must be > 0, got 0" }, models.arch, { shape = "segmental", rise = 0 })
    expect_error({ "models.arch: thickness must be < 2 * rise (1), got 1" }, models.arch,
      { shape = "segmental", rise = 0.5, thickness = 1 })
    expect_error({ "models.arch: thickness must be < 2 * the smallest radius of curvature of the ellipse (0.4), got 1" },
      models.arch, { shape = "elliptical", span = 10, rise = 1, thickness = 1 })
    expect_error({ "models.arch: thickness must be < 2 * the catenary's radius of curvature at the crown" },
      models.arch, { shape = "catenary", span = 10, rise = 8, thickness = 5 })
    expect_error({ "models.arch: joints = \"vertical\" is available for the circular shapes", "not for a catenary arch" },
      models.arch, { shape = "catenary", joints = "vertical" })
    expect_error({ "models.arch: joints = \"vertical\": joint 1 at x = ", "misses the intrados" }, models.arch,
      { joints = "vertical" })
    -- The radial joint next to a vertical apex joint crosses it when the
    -- voussoirs are short against the thickness.
    expect_error({ "models.arch: voussoir 128 is degenerate" }, models.arch,
      { shape = "pointed", eccentricity = 0.1, thickness = 1.5, voussoirs = 256 })
  end)
end)

describe("models.arch equilibrium", function()
  local function stands(o)
    local r = ashlar.analyze(models.arch(o), { friction = math.huge })
    assert.equal("converged", r.status)
    return r.stable
  end

  -- Independent of the solver: a symmetric arch without sliding stands iff
  -- a symmetric thrust line does (average any equilibrium with its mirror
  -- image): a horizontal crown thrust H at height z on the crown joint
  -- whose line, with the weights of the left half added joint by joint,
  -- crosses every joint between intrados and extrados in compression.
  -- Linear in (H, G = H z): a 2-D LP, decided at the vertices of its
  -- region (which lies in the pointed cone H >= 0, z on the crown joint).
  local function thrust_line_stands(s, n)
    local m = n // 2
    local j = joints(s, n)
    local rows = {}   -- { cH, cG, c0 }: cH H + cG G + c0 >= 0
    rows[#rows + 1] = { 1, 0, 0 }
    rows[#rows + 1] = { -j[m].i[2], 1, 0 }  -- z >= intrados of the crown joint
    rows[#rows + 1] = { j[m].e[2], -1, 0 }  -- z <= extrados
    for k = 0, m - 1 do
      local weight, moment = 0, 0           -- of voussoirs k + 1 .. m (mass; g cancels)
      for b = k + 1, m do
        weight = weight + s:block(b):mass()
        moment = moment + s:block(b):mass() * s:block(b):centroid()[1]
      end
      -- The joint's reaction on the part above is (H, weight). Its moments
      -- about the intrados and extrados points must be <= 0 and >= 0, and
      -- (E - I) x (H, weight) <= 0 (compression).
      for _, point in ipairs{ { j[k].i, -1 }, { j[k].e, 1 } } do
        local p, sign = point[1], point[2]
        -- M_P = -H (z - p_z) + sum W (x - p_x) = -G + H p_z + moment - weight p_x
        rows[#rows + 1] = { sign * p[2], -sign, sign * (moment - weight * p[1]) }
      end
      local dx, dz = j[k].e[1] - j[k].i[1], j[k].e[2] - j[k].i[2]
      rows[#rows + 1] = { dz, 0, -dx * weight }
    end
    local function feasible(H, G)
      for _, r in ipairs(rows) do
        if r[1] * H + r[2] * G + r[3] < -1e-9 * (1 + math.abs(H) + math.abs(G)) then return false end
      end
      return true
    end
    for a = 1, #rows do
      for b = a + 1, #rows do
        local p, q = rows[a], rows[b]
        local det = p[1] * q[2] - p[2] * q[1]
        if det ~= 0 then
          local H = (-p[3] * q[2] + p[2] * q[3]) / det
          local G = (-p[1] * q[3] + p[3] * q[1]) / det
          if feasible(H, G) then return true end
        end
      end
    end
    return false
  end

  -- Smallest thickness / radius at which the arch stands, by bisection.
  local function minimum_ratio(shape, eccentricity, judge)
    local function ok(ratio)
      local o = { shape = shape, radius = 5, eccentricity = eccentricity, thickness = ratio * 5, voussoirs = 16 }
      if judge then return judge(models.arch(o), 16) end
      return stands(o)
    end
    local failing, standing = 0.03, 0.2
    assert(not ok(failing) and ok(standing), "the bracket does not hold the minimum thickness")
    while standing - failing > 1e-5 do
      local middle = (failing + standing) / 2
      if ok(middle) then standing = middle else failing = middle end
    end
    return (failing + standing) / 2
  end

  it("finds the pointed arch's minimum thickness below the semicircle's", function()
    local semicircle = minimum_ratio("semicircular")
    -- Eccentricity 0 is the semicircle: the polyhedral 16-voussoir minimum
    -- of models_spec.lua, found there by the thrust-line method.
    near(minimum_ratio("pointed", 0), 0.1070762, 2e-5, "pointed, eccentricity 0")
    near(semicircle, 0.1070762, 2e-5, "semicircle")
    local pointed = minimum_ratio("pointed", 0.2)
    assert.is_true(pointed < semicircle - 0.02, ("pointed %g, semicircle %g"):format(pointed, semicircle))
    near(pointed, 0.0703236, 2e-5, "pointed, eccentricity 0.2")
    -- The thrust-line method finds the same minima.
    near(minimum_ratio("pointed", 0.2, thrust_line_stands), pointed, 2e-5, "pointed, by the thrust line")
    near(minimum_ratio("semicircular", nil, thrust_line_stands), 0.1070762, 2e-5, "semicircle, by the thrust line")
  end)

  it("stands when ample and falls when thin", function()
    for _, shape in ipairs{ "pointed", "segmental", "elliptical", "catenary" } do
      assert.is_true(stands{ shape = shape, thickness = 0.8 }, shape .. " ample")
      -- The catenary is the funicular of its own (uniform) weight: it
      -- stands however thin.
      assert.equal(shape == "catenary", stands{ shape = shape, thickness = 0.05 }, shape .. " thin")
    end
  end)
end)
