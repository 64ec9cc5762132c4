-- models.arch_bridge: block counts and names, every contact the topology
-- implies (and no other), the exact polyhedral volume against a closed
-- form, symmetry about x = 0, the ground support, option errors, and
-- equilibrium of the default bridge and of bare thin arches.
local ashlar = require "ashlar"
local arch_bridge = require "ashlar.models.arch_bridge"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_generator_error

-- The expected contacts as a set of "name|name" pairs (sorted names), from
-- the construction: spans S, voussoirs N, courses C.
local function expected_pairs(S, N, C, spandrel, deck)
  local pairs_ = {}
  local function add(a, b)
    if a > b then a, b = b, a end
    pairs_[a .. "|" .. b] = true
  end
  local function v(p, k) return ("span %d voussoir %d"):format(p, k) end
  local function sp(p, k) return ("spandrel %d %d"):format(p, k) end
  local function pier(p, c) return ("pier %d course %d"):format(p, c) end
  for p = 1, S do
    for k = 1, N - 1 do add(v(p, k), v(p, k + 1)) end
    add(v(p, 1), p == 1 and "abutment left" or pier(p - 1, C))
    add(v(p, N), p == S and "abutment right" or pier(p, C))
    if spandrel then
      for k = 1, N do add(v(p, k), sp(p, k)) end
      for k = 1, N - 1 do add(sp(p, k), sp(p, k + 1)) end
      add(sp(p, 1), p == 1 and "abutment left" or ("pier %d fill"):format(p - 1))
      add(sp(p, N), p == S and "abutment right" or ("pier %d fill"):format(p))
    end
  end
  for p = 1, S - 1 do
    for c = 1, C - 1 do add(pier(p, c), pier(p, c + 1)) end
    add(pier(p, 1), "ground")
    if spandrel then add(("pier %d fill"):format(p), pier(p, C)) end
  end
  add("abutment left", "ground"); add("abutment right", "ground")
  local level = {}
  if deck then
    level[1] = "abutment left"
    for p = 1, S do
      for k = 1, N do level[#level + 1] = sp(p, k) end
      if p < S then level[#level + 1] = ("pier %d fill"):format(p) end
    end
    level[#level + 1] = "abutment right"
    for i, name in ipairs(level) do
      add(("deck %d"):format(i), name)
      if i > 1 then add(("deck %d"):format(i - 1), ("deck %d"):format(i)) end
    end
  end
  return pairs_, #level
end

local function found_pairs(s)
  local found, count = {}, 0
  for _, f in ipairs(s:interfaces()) do
    local a, b = s:name(f.a), s:name(f.b)
    if a > b then a, b = b, a end
    local key = a .. "|" .. b
    assert(not found[key], "two interfaces between " .. key)
    found[key] = f
    count = count + 1
  end
  return found, count
end

local function check_topology(s, S, N, C, spandrel, deck)
  local expected, decks = expected_pairs(S, N, C, spandrel, deck)
  local found, count = found_pairs(s)
  for key in pairs(expected) do assert(found[key], "missing contact " .. key) end
  for key in pairs(found) do assert(expected[key], "spurious contact " .. key) end
  local n_expected = 0
  for _ in pairs(expected) do n_expected = n_expected + 1 end
  assert.equal(n_expected, count)
  return found, count, decks
end

-- Closed-form volume of the free blocks of a bridge of circular arches
-- (segmental or semicircular) with spandrels and deck: the envelope from
-- the ground to the deck's top minus, under each arch, the opening: the
-- rectangle below the springing and the polygon under the intrados chords
-- (a fan of N triangles from the circle's centre, less the triangle under
-- the springing line when the centre is below it).
local function closed_volume(o)
  local span, t, N, S = o.span, o.thickness, o.voussoirs, o.spans
  local r, zc
  if o.shape == "semicircular" then r, zc = span / 2, 0
  else r = (span ^ 2 / 4 + o.rise ^ 2) / (2 * o.rise); zc = o.rise - r end
  local ri, ro = r - t / 2, r + t / 2
  local half_clear = math.sqrt(ri * ri - zc * zc)
  local phi0 = math.atan(-zc, -half_clear)     -- intrados springing angle
  local step = 2 * (phi0 - math.pi / 2) / N
  local top = N % 2 == 1 and zc + ro * math.cos(step / 2) or zc + ro
  local H = top + (o.cover or t / 2)
  local deck = o.deck_thickness or 0.3
  local length = S * 2 * half_clear + (S - 1) * o.pier_width + 2 * o.abutment_width
  local opening = 2 * half_clear * o.pier_height + N * 0.5 * ri * ri * math.sin(step) - half_clear * (-zc)
  return o.depth * (length * (o.pier_height + H + deck) - S * opening), H
end

local defaults = { spans = 3, span = 8, rise = 3, thickness = 0.6, depth = 4, voussoirs = 26,
                   pier_width = 1.5, pier_height = 4, pier_courses = 4, abutment_width = 3 }
local function with(changes)
  local o = {}
  for k, v in pairs(defaults) do o[k] = v end
  for k, v in pairs(changes or {}) do o[k] = v end
  return o
end

describe("models.arch_bridge (defaults)", function()
  local s = arch_bridge()

  it("has the arches, spandrels, piers, fills, abutments, deck and one ground support", function()
    -- 3 x 26 voussoirs, 3 x 26 spandrels, 2 piers x 4 courses, 2 pier fills,
    -- 2 abutments, 82 deck blocks, the ground.
    assert.equal(78 + 78 + 8 + 2 + 2 + 82 + 1, #s)
    for p = 1, 3 do
      for k = 1, 26 do
        assert.equal((p - 1) * 26 + k, s:find(("span %d voussoir %d"):format(p, k)))
        assert.truthy(s:find(("spandrel %d %d"):format(p, k)))
      end
    end
    for p = 1, 2 do
      for c = 1, 4 do assert.truthy(s:find(("pier %d course %d"):format(p, c))) end
      assert.truthy(s:find(("pier %d fill"):format(p)))
    end
    for i = 1, 82 do assert.truthy(s:find(("deck %d"):format(i))) end
    assert.truthy(s:find("abutment left")); assert.truthy(s:find("abutment right"))
    for i = 1, #s do assert.equal(s:name(i) == "ground", s:is_support(i)) end
    -- Spans left to right, voussoirs left to right within a span.
    for i = 2, 78 do assert.is_true(s:block(i):centroid()[1] > s:block(i - 1):centroid()[1]) end
  end)

  it("has exactly the contacts of the construction (415)", function()
    local found, count, decks = check_topology(s, 3, 26, 4, true, true)
    assert.equal(82, decks)
    assert.equal(415, count)
    -- Each spandrel block rests on the whole extrados face of its voussoir.
    for p = 1, 3 do
      for k = 1, 26 do
        local v = ("span %d voussoir %d"):format(p, k)
        local f = found[v .. "|" .. ("spandrel %d %d"):format(p, k)]
        local block = s:block(v)
        -- The extrados face: the face whose plane holds the contact.
        local best = 0
        local vertices = block:vertices()
        for _, face in ipairs(block:faces()) do
          local on = true
          for _, i in ipairs(face) do
            local x = vertices[i]
            local d = (x[1] - f.center[1]) * f.normal[1] + (x[2] - f.center[2]) * f.normal[2]
              + (x[3] - f.center[3]) * f.normal[3]
            on = on and math.abs(d) < 1e-9
          end
          if on then
            local p1, p2, p3 = vertices[face[1]], vertices[face[2]], vertices[face[3]]
            local ux, uz = p2[1] - p1[1], p2[3] - p1[3]
            local wx, wz = p3[1] - p2[1], p3[3] - p2[3]
            best = math.sqrt(ux * ux + uz * uz + wx * wx + wz * wz) -- chord (one of the two edges is along y)
          end
        end
        near(f.area, best * 4, 1e-9, "spandrel " .. p .. " " .. k .. " contact is the whole extrados face")
      end
    end
  end)

  it("has the closed-form polyhedral volume", function()
    local expected, H = closed_volume(with{ shape = "segmental" })
    near(support.free_volume(s), expected, 1e-9 * expected)
    local lo, hi = s:bounds()
    near(hi[3], H + 0.3, 1e-12, "deck top")
    near(lo[3], -4 - 0.6, 1e-12, "ground bottom")
    near(hi[1], -lo[1], 1e-12); near(hi[2], 2, 1e-15); near(lo[2], -2, 1e-15)
  end)

  it("is symmetric about x = 0", function()
    local function mirror(name)
      local p, k = name:match("^span (%d+) voussoir (%d+)$")
      if p then return ("span %d voussoir %d"):format(4 - p, 27 - k) end
      p, k = name:match("^spandrel (%d+) (%d+)$")
      if p then return ("spandrel %d %d"):format(4 - p, 27 - k) end
      local c
      p, c = name:match("^pier (%d+) course (%d+)$")
      if p then return ("pier %d course %d"):format(3 - p, c) end
      p = name:match("^pier (%d+) fill$")
      if p then return ("pier %d fill"):format(3 - p) end
      p = name:match("^deck (%d+)$")
      if p then return ("deck %d"):format(83 - p) end
      return ({ ["abutment left"] = "abutment right", ["abutment right"] = "abutment left", ground = "ground" })[name]
    end
    for i = 1, #s do
      local other = s:find(assert(mirror(s:name(i)), s:name(i)))
      local c, m = s:block(i):centroid(), s:block(other):centroid()
      near(c[1], -m[1], 1e-12, s:name(i)); near(c[3], m[3], 1e-12, s:name(i)); near(c[2], 0, 1e-12)
      near(s:block(i):volume(), s:block(other):volume(), 1e-12 * s:block(i):volume(), s:name(i))
    end
  end)

  it("stands (friction 0.7)", function()
    local r = ashlar.analyze(s, { friction = 0.7 })
    assert.equal("converged", r.status)
    assert.is_true(r.stable)
    assert.equal(0, #r.floating)
  end)
end)

describe("models.arch_bridge variants", function()
  it("builds every shape, span count and voussoir parity with the same topology", function()
    for _, o in ipairs{
      { shape = "semicircular", spans = 2, voussoirs = 9, pier_courses = 3 },
      { shape = "elliptical", spans = 1, voussoirs = 10 },
      { shape = "catenary", spans = 4, voussoirs = 8, pier_courses = 1 },
      { shape = "segmental", spans = 2, voussoirs = 2, deck = { thickness = 0.5 } },
    } do
      local s = arch_bridge(o)
      local S, N, C = o.spans, o.voussoirs, o.pier_courses or 4
      local M = S * N + S + 1
      assert.equal(2 * S * N + (S - 1) * (C + 1) + 2 + M + 1, #s)
      local _, count = check_topology(s, S, N, C, true, true)
      assert.equal(S * (N - 1) * 2 + S * N + 4 * S + (S - 1) * (C + 1) + 2 + 2 * M - 1, count)
    end
  end)

  it("has the closed-form volume for semicircular arches, an even count and a thick deck", function()
    local o = with{ shape = "semicircular", spans = 2, voussoirs = 12, cover = 0.5, deck_thickness = 0.4 }
    local s = arch_bridge{ shape = "semicircular", spans = 2, voussoirs = 12, cover = 0.5, deck = { thickness = 0.4 } }
    local expected = closed_volume(o)
    near(support.free_volume(s), expected, 1e-9 * expected)
  end)

  it("without spandrels: bare rings on piers and box abutments, no deck", function()
    local s = arch_bridge{ spandrel = false }
    assert.equal(78 + 8 + 2 + 1, #s)
    assert.is_nil(s:find("deck 1")); assert.is_nil(s:find("spandrel 1 1")); assert.is_nil(s:find("pier 1 fill"))
    local _, count = check_topology(s, 3, 26, 4, false, false)
    assert.equal(91, count)
    -- Ring: the segment under the extrados chords minus the one under the
    -- intrados chords (each a fan from the centre less the triangle under
    -- the springing line), joints equal in angle between the intrados
    -- springings; the first voussoir reaches down to z = 0 at the extrados.
    local r = (16 + 9) / 6
    local zc = 3 - r
    local ri, ro = r - 0.3, r + 0.3
    local xi, xe = math.sqrt(ri * ri - zc * zc), math.sqrt(ro * ro - zc * zc)
    local phi0 = math.atan(-zc, -xi)
    local step = 2 * (phi0 - math.pi / 2) / 26
    local under_intrados = 26 * 0.5 * ri * ri * math.sin(step) - xi * (-zc)
    local end_angle = math.atan(-zc, -xe) - (phi0 - step) -- from e0 to joint 1
    local under_extrados = ro * ro * math.sin(end_angle) + 24 * 0.5 * ro * ro * math.sin(step) - xe * (-zc)
    local expected = 4 * (3 * (under_extrados - under_intrados) + 2 * 1.5 * 4 + 2 * 3 * 4)
    near(support.free_volume(s), expected, 1e-9 * expected)
  end)

  it("stands with a ring of 0.25 and falls with one of 0.15 without spandrels; spandrels hold even 0.05", function()
    assert.is_true(ashlar.analyze(arch_bridge{ spandrel = false, thickness = 0.25 }, { friction = 0.7 }).stable)
    local r = ashlar.analyze(arch_bridge{ spandrel = false, thickness = 0.15 }, { friction = 0.7 })
    assert.equal("converged", r.status)
    assert.is_false(r.stable)
    assert.is_true(r.infeasibility > 0.01)
    assert.is_true(ashlar.analyze(arch_bridge{ thickness = 0.05 }, { friction = 0.7 }).stable)
  end)
end)

describe("models.arch_bridge in the FEA", function()
  -- The FEA meshes hexahedra: with spandrels the abutments are L-shaped
  -- prisms (12 corners), and the message says so and what to do; the advice
  -- holds, the bridge without spandrels meshes (every block 8 corners).
  it("names the L-shaped abutment and the way out, which works", function()
    local o = { spans = 1, voussoirs = 8, pier_courses = 1 }
    local message = support.expect_error({ "block 17 ('abutment left') is not a hexahedron (12 vertices)",
      "an arch bridge's abutments, L-shaped to back the spandrels (use spandrel = false)" }, ashlar.fea,
      arch_bridge(o), { refine = 1 })
    assert.is_nil(message:find("a dome needs an oculus", 1, true))
    o.spandrel = false
    local fe = ashlar.fea(arch_bridge(o), { refine = 1 })
    assert.equal(8 + 2, fe.element_count)  -- 8 voussoirs and 2 abutments, one element each
  end)
end)

describe("models.arch_bridge options", function()
  it("rejects bad options, naming models.arch_bridge", function()
    expect_error({ "models.arch_bridge: unknown option 'radius' (allowed: abutment_width, cover, deck, density, depth,",
                   "voussoirs" }, arch_bridge, { radius = 5 })
    expect_error({ "models.arch_bridge: expected an option table, got number" }, arch_bridge, 3)
    expect_error({ "models.arch_bridge: spans: must be >= 1, got 0" }, arch_bridge, { spans = 0 })
    expect_error({ "models.arch_bridge: spans: expected an integer, got 1.5" }, arch_bridge, { spans = 1.5 })
    expect_error({ "models.arch_bridge: voussoirs: must be >= 2, got 1" }, arch_bridge, { voussoirs = 1 })
    expect_error({ "models.arch_bridge: pier_courses: must be >= 1, got 0" }, arch_bridge, { pier_courses = 0 })
    expect_error({ "models.arch_bridge: span: must be > 0, got -8" }, arch_bridge, { span = -8 })
    expect_error({ "models.arch_bridge: shape: 'pointed' is not one of segmental, semicircular, elliptical, catenary" },
      arch_bridge, { shape = "pointed" })
    expect_error({ "models.arch_bridge: rise: a segmental arch needs rise < span / 2 (4), got 4" }, arch_bridge,
      { rise = 4 })
    expect_error({ "models.arch_bridge: rise: not an option of a semicircular arch" }, arch_bridge,
      { shape = "semicircular", rise = 4 })
    expect_error({ "models.arch_bridge: thickness must be < 2 * rise (2), got 2" }, arch_bridge,
      { rise = 1, thickness = 2 })
    expect_error({ "models.arch_bridge: thickness must be < span (8), got 8" }, arch_bridge,
      { shape = "semicircular", thickness = 8 })
    expect_error({ "models.arch_bridge: pier_width must be > the two springing joints' length" }, arch_bridge,
      { pier_width = 1 })
    expect_error({ "models.arch_bridge: abutment_width must be > the springing joint's length" }, arch_bridge,
      { abutment_width = 0.5 })
    expect_error({ "models.arch_bridge: deck needs spandrel = true" }, arch_bridge, { spandrel = false, deck = true })
    expect_error({ "models.arch_bridge: cover: only with spandrel = true" }, arch_bridge,
      { spandrel = false, cover = 1 })
    expect_error({ "models.arch_bridge: deck: expected a boolean or a table, got number" }, arch_bridge, { deck = 1 })
    expect_error({ "models.arch_bridge: deck: unknown option 'width' (allowed: thickness)" }, arch_bridge,
      { deck = { width = 1 } })
    expect_error({ "models.arch_bridge: deck: thickness: must be > 0, got 0" }, arch_bridge,
      { deck = { thickness = 0 } })
    expect_error({ "models.arch_bridge: spandrel: expected a boolean, got string" }, arch_bridge, { spandrel = "yes" })
  end)
end)
