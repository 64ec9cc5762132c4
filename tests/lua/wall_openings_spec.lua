-- models.wall{ openings = ... }: volumes against closed forms (lintel heads:
-- the wall less the openings; arch heads: the voussoir ring and the wall
-- less the opening and the polygon under the intrados chords), no
-- overlaps, every block in contact, equilibrium with the support reaction
-- equal to the weight, and the errors for bad openings.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_generator_error

local G = 9.81

-- Every free block touches some block, and no two blocks interpenetrate.
local function expect_jointed(s)
  assert.equal(0, #s:overlaps())
  local touched = {}
  for _, f in ipairs(s:interfaces()) do touched[f.a], touched[f.b] = true, true end
  for i = 1, #s do assert(touched[i], s:name(i) .. " touches nothing") end
end

describe("models.wall with openings", function()
  -- 10 bricks x 12 courses; a door (6 courses) and a window (sill 3
  -- courses, 4 high), both 2 bricks wide, under lintels.
  local lintels = { length = 2.4, height = 0.84, openings = {
    { x = 0.48, width = 0.48, height = 0.42 },
    { x = 1.44, sill = 0.21, width = 0.48, height = 0.28, bearing = 0.12, lintel_height = 0.07 } } }

  it("with lintels: the wall's volume less the openings', lintels on their bearings", function()
    local s = models.wall(lintels)
    local t = 0.11
    local expected = (2.4 * 0.84 - 0.48 * 0.42 - 0.48 * 0.28) * t
    near(support.free_volume(s), expected, 1e-9 * expected, "volume")
    expect_jointed(s)
    -- Every block is a box: two overlap exactly when their bounding boxes share a volume.
    for i = 1, #s do
      local lo_i, hi_i = s:block(i):bounds()
      for j = i + 1, #s do
        local lo_j, hi_j = s:block(j):bounds()
        local apart = false
        for k = 1, 3 do apart = apart or math.min(hi_i[k], hi_j[k]) - math.max(lo_i[k], lo_j[k]) <= 1e-12 end
        assert(apart, s:name(i) .. " overlaps " .. s:name(j))
      end
    end
    -- The lintels: opening width + 2 bearings long, resting on the bearings only.
    for n, o in ipairs{ { b = 0.24, lh = 0.14, top = 0.42 }, { b = 0.12, lh = 0.07, top = 0.49 } } do
      local i = s:find(("opening %d lintel"):format(n))
      near(s:block(i):volume(), (0.48 + 2 * o.b) * o.lh * t, 1e-12, "lintel volume")
      local bearing = 0
      for _, f in ipairs(s:interfaces()) do
        if (f.a == i or f.b == i) and math.abs(f.center[3] - o.top) < 1e-9 then bearing = bearing + f.area end
      end
      near(bearing, 2 * o.b * t, 1e-12, "bearing area")
    end
  end)

  it("with a semicircular arch head: the ring's and the wall's closed-form volumes", function()
    local w, ring, n, t = 0.72, 0.24, 15, 0.11
    local s = models.wall{ length = 2.4, height = 1.12, openings = {
      { x = 0.72, sill = 0.14, width = w, height = 0.28, head = "arch", voussoirs = n, ring = ring } } }
    -- Polyhedral voussoirs (chords): N/2 (Ro^2 - Ri^2) sin(pi/N) per unit depth, which
    -- tends to the annulus's pi/2 (Ro^2 - Ri^2) as N grows.
    local ri, ro = w / 2, w / 2 + ring
    local ring_volume = 0
    for k = 1, n do ring_volume = ring_volume + s:block(s:find(("opening 1 voussoir %d"):format(k))):volume() end
    local expected_ring = n / 2 * (ro * ro - ri * ri) * math.sin(math.pi / n) * t
    near(ring_volume, expected_ring, 1e-9 * expected_ring, "ring volume")
    assert.is_true(ring_volume < math.pi / 2 * (ro * ro - ri * ri) * t)
    local expected = (2.4 * 1.12 - w * 0.28 - n / 2 * ri * ri * math.sin(math.pi / n)) * t
    near(support.free_volume(s), expected, 1e-9 * expected, "wall volume")
    expect_jointed(s)
    -- The courses meet the ring along its whole extrados (N chords of
    -- 2 Ro sin(pi / 2N)) and carry it on both springings (ring wide).
    local function voussoir(i) return s:name(i):find("voussoir") ~= nil end
    local area = 0
    for _, f in ipairs(s:interfaces()) do
      if voussoir(f.a) ~= voussoir(f.b) then area = area + f.area end
    end
    local expected_area = (2 * n * ro * math.sin(math.pi / (2 * n)) + 2 * ring) * t
    near(area, expected_area, 1e-9 * expected_area, "area of the ring's contacts with the courses")
    -- rise = width / 2, given, is the default semicircle.
    local given = models.wall{ length = 2.4, height = 1.12, openings = {
      { x = 0.72, sill = 0.14, width = w, height = 0.28, head = "arch", voussoirs = n, ring = ring, rise = w / 2 } } }
    assert.equal(#s, #given)
    near(support.free_volume(given), expected, 1e-9 * expected, "wall volume, rise given")
  end)

  it("with a segmental arch head: the wall less the opening and the segment under the intrados chords", function()
    local w, rise, n, t = 0.96, 0.21, 9, 0.11
    local s = models.wall{ length = 2.4, height = 1.05, openings = {
      { x = 0.72, sill = 0.21, width = w, height = 0.28, head = "arch", rise = rise, voussoirs = n } } }
    -- Joints equal in angle between the intrados springings: a fan of N
    -- triangles from the centre less the triangle under the springing line.
    local ri = (w * w / 4 + rise * rise) / (2 * rise)
    local zc = rise - ri
    local phi0 = math.atan(-zc, -w / 2)
    local step = 2 * (phi0 - math.pi / 2) / n
    local under_intrados = n * 0.5 * ri * ri * math.sin(step) - w / 2 * (-zc)
    local expected = (2.4 * 1.05 - w * 0.28 - under_intrados) * t
    near(support.free_volume(s), expected, 1e-9 * expected, "wall volume")
    assert.equal(#s, s:find(("opening 1 voussoir %d"):format(n)))  -- the ring, last
    expect_jointed(s)
  end)

  it("a wall with a door and an arched window stands, the ground carrying its weight", function()
    local s = models.wall{ length = 2.88, height = 1.4, openings = {
      { x = 0.48, width = 0.72, height = 0.84 },
      { x = 1.68, sill = 0.42, width = 0.72, height = 0.28, head = "arch" } } }
    local r = ashlar.analyze(s, { friction = 0.7 })
    assert.is_true(r.stable)
    local ground, weight, reaction = s:find("ground"), 0, 0
    for i = 1, #s do if not s:is_support(i) then weight = weight + s:block(i):mass() * G end end
    for _, f in ipairs(r.interfaces) do
      if f.a == ground then reaction = reaction + f.resultant[3] elseif f.b == ground then reaction = reaction - f.resultant[3] end
    end
    near(reaction, weight, 1e-6 * weight, "support reaction")
  end)

  it("meshes for the FEA with lintels; with an arch head the message names the cut bricks and the way out", function()
    local small = { length = 1.2, height = 0.42, openings = { { x = 0.24, width = 0.48, height = 0.21 } } }
    local s = models.wall(small)
    local fe = ashlar.fea(s, { refine = 1 })
    assert.equal(#s - 1, fe.element_count)  -- every free block a box, one element each
    small.height, small.openings[1].head = 0.7, "arch"
    expect_error({ "is not a hexahedron", "a wall's bricks cut around an arch head (use a lintel)" }, ashlar.fea,
      models.wall(small), { refine = 1 })
  end)

  it("rejects bad openings, naming the opening, what was wrong and the value", function()
    local wall = models.wall
    local function with(opening, extra)
      local o = { length = 2.4, height = 0.84, openings = { { x = 0.48, width = 0.48, height = 0.28 }, opening } }
      for k, v in pairs(extra or {}) do o[k] = v end
      return o
    end
    expect_error({ "models.wall: openings[2]: x 0.12 leaves less than a brick (0.24) between the wall's left end" },
      wall, with{ x = 0.12, width = 0.48, height = 0.28 })
    expect_error({ "models.wall: openings[2]: x + width 2.28 leaves less than a brick (0.24) between the jamb and the wall's right end (2.4)" },
      wall, with{ x = 1.8, width = 0.48, height = 0.28 })
    expect_error({ "models.wall: openings[2]: x 1.25 is not a whole number of half bricks (0.12)" },
      wall, with{ x = 1.25, width = 0.48, height = 0.28 })
    expect_error({ "models.wall: openings[2]: height 0.3 is not a whole number of courses (0.07)" },
      wall, with{ x = 1.44, width = 0.48, height = 0.3 })
    expect_error({ "models.wall: openings[2]: width: required (m)" }, wall, with{ x = 1.44, height = 0.28 })
    expect_error({ "models.wall: openings[2]: unknown option 'y'" }, wall, with{ x = 1.44, y = 0, width = 0.48, height = 0.28 })
    expect_error({ "models.wall: openings[1] (x from 0.48 to 0.96, with its head 0.24 to 1.2) and openings[2] (x from 1.08 to 1.56",
                   "overlap or leave less than a brick (0.24) between their jambs" },
      wall, with{ x = 1.08, width = 0.48, height = 0.28 })
    expect_error({ "models.wall: openings[2]: the lintel's top (z = 0.98) is above the wall's (0.84)" },
      wall, with{ x = 1.44, sill = 0.42, width = 0.48, height = 0.42 })
    expect_error({ "models.wall: openings[2]: the arch's top (z = ", ") is above the wall's (0.84)" },
      wall, with{ x = 1.44, sill = 0.35, width = 0.48, height = 0.21, head = "arch" })
    expect_error({ "models.wall: openings[2]: rise must be <= width / 2 (0.24; a semicircle), got 0.3" },
      wall, with{ x = 1.44, width = 0.48, height = 0.28, head = "arch", rise = 0.3 })
    expect_error({ 'models.wall: openings[2]: bearing: only for head = "lintel", not "arch"' },
      wall, with{ x = 1.44, width = 0.48, height = 0.28, head = "arch", bearing = 0.24 })
    expect_error({ "models.wall: openings[2]: head: 'flat' is not one of lintel, arch" },
      wall, with{ x = 1.44, width = 0.48, height = 0.28, head = "flat" })
    expect_error({ "models.wall: openings: expected a list of opening tables" }, wall,
      { length = 2.4, openings = { x = 0.48, width = 0.48, height = 0.28 } })
  end)
end)
