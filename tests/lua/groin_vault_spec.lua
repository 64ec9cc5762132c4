-- models.groin_vault: blocks and courses (stacked and running bond),
-- contacts implied by the topology (course joints within a row, bed joints
-- between overlapping pieces of adjacent rows, groin joints between the
-- webs, springings) with their areas, the volume of the polyhedral shape
-- (the same cut or not) and its convergence to the circular groin vault,
-- the square's symmetries, option errors, and an ample vault standing.
local ashlar = require "ashlar"
local groin_vault = require "ashlar.models.groin_vault"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

local webs = { "north", "west", "south", "east" }
local left_of = { north = "west", west = "south", south = "east", east = "north" }
-- A web's coordinate v along its axis, towards its face, from x and y.
local along = {
  north = function(x, y) return y end, west = function(x, y) return -x end,
  south = function(x, y) return -y end, east = function(x, y) return x end,
}

-- Polyhedral volume: web "north" voussoir i is its section P_i (a
-- trapezoid of the annulus, on one side of x = 0) extruded from y = |x| to
-- y = side / 2, so its volume is area(P_i) * (side / 2 - |centroid_x(P_i)|).
local function polyhedral_volume(radius, thickness, voussoirs, side)
  local inner, outer = radius - thickness / 2, radius + thickness / 2
  local function corner(k, r)
    local angle = math.pi * (1 - k / voussoirs)
    return { r * math.cos(angle), r * math.sin(angle) }
  end
  local web = 0
  for i = 1, voussoirs do
    local p = { corner(i - 1, inner), corner(i - 1, outer), corner(i, outer), corner(i, inner) }
    local area, moment = 0, 0
    for j = 1, 4 do
      local a, b = p[j], p[j % 4 + 1]
      local cross = a[1] * b[2] - b[1] * a[2]
      area, moment = area + cross / 2, moment + (a[1] + b[1]) * cross / 6
    end
    web = web + math.abs(area) * (side / 2 - math.abs(moment / area))
  end
  return 4 * web
end

-- The circular groin vault: four webs {r in [inner, outer], |x| <= y <= side / 2}.
local function exact_volume(radius, thickness, side)
  local inner, outer = radius - thickness / 2, radius + thickness / 2
  return 4 * (side / 2 * math.pi / 2 * (outer ^ 2 - inner ^ 2) - 2 / 3 * (outer ^ 3 - inner ^ 3))
end

-- Area of voussoir i's section (a trapezoid of the annulus) and its
-- corners' largest |u| (the row's furthest groin corner).
local function section(radius, thickness, voussoirs, i)
  local inner, outer = radius - thickness / 2, radius + thickness / 2
  local a0, a1 = math.pi * (1 - (i - 1) / voussoirs), math.pi * (1 - i / voussoirs)
  local area = (outer ^ 2 - inner ^ 2) / 2 * math.sin(a0 - a1)
  return area, outer * math.max(math.abs(math.cos(a0)), math.abs(math.cos(a1)))
end

-- Reads the blocks back: rows[web][i] is the list of voussoir i's pieces
-- from the groin to the face, each { index, lo, hi } with lo, hi its extent
-- along the web's axis (lo = -inf for the piece on the groin).
local function rows_of(s, voussoirs)
  local rows = {}
  for _, web in ipairs(webs) do
    rows[web] = {}
    for i = 1, voussoirs do rows[web][i] = {} end
  end
  for index = 1, #s do
    local web, i, c = s:name(index):match("^(%a+) voussoir (%d+) course (%d+)$")
    if web then
      local row = rows[web][tonumber(i)]
      assert.equal(#row + 1, tonumber(c), "courses in order")
      local lo, hi = s:block(index):bounds()
      local a, b = along[web](lo[1], lo[2]), along[web](hi[1], hi[2])
      row[#row + 1] = { index = index, lo = c == "1" and -math.huge or math.min(a, b), hi = math.max(a, b) }
    end
  end
  return rows
end

-- Checks a vault's pieces and its contacts against the topology: course
-- joints within a row, bed joints between overlapping pieces of adjacent
-- rows (with their areas), groins, springings. Returns the contact count.
local function check_topology(s, o)
  local radius, thickness, n = o.radius or 3, o.thickness or 0.6, o.voussoirs or 22
  local inner, outer = radius - thickness / 2, radius + thickness / 2
  local half = (o.side or 2 * (radius + thickness)) / 2
  local course = (half - outer * math.sin(math.pi / n)) / (o.courses or 4)
  local rows = rows_of(s, n)
  local blocks = 4
  for _, web in ipairs(webs) do
    for i = 1, n do
      local row, _, reach = rows[web][i], section(radius, thickness, n, i)
      blocks = blocks + #row
      -- Flush at the face; whole courses, but a half course at the face of
      -- every second row in running bond; the groin piece at least half a
      -- course long at its shortest.
      local shifted = o.bond == "running" and math.min(i, n + 1 - i) % 2 == 0
      near(row[#row].hi, half, 1e-12, "flush face")
      for c = 2, #row do
        near(row[c].lo, row[c - 1].hi, 1e-12, "course joint")
        local length = (shifted and c == #row) and course / 2 or course
        near(row[c].hi - row[c].lo, length, 1e-12, "course length")
      end
      if #row > 1 then assert.is_true(row[1].hi - reach >= course / 2 * (1 - 1e-9), "groin piece too short") end
    end
  end
  assert.equal(blocks, #s)

  local expected = {}
  local function add(a, b, area)
    expected[math.min(a, b) .. "-" .. math.max(a, b)] = area or true
  end
  local springing = { north = { "northwest", "northeast" }, west = { "southwest", "northwest" },
                      south = { "southeast", "southwest" }, east = { "northeast", "southeast" } }
  for _, web in ipairs(webs) do
    for i = 1, n do
      local row = rows[web][i]
      local area = section(radius, thickness, n, i)
      for c = 2, #row do add(row[c - 1].index, row[c].index, area) end
      if i < n then
        -- Bed joint k = i: a rectangle thickness wide along the axis,
        -- cut by the groin line v = r |cos| on the groin pieces.
        local cos = math.abs(math.cos(math.pi * (1 - i / n)))
        if 2 * i == n then cos = 0 end
        for _, p in ipairs(row) do
          for _, q in ipairs(rows[web][i + 1]) do
            local lo, hi = math.max(p.lo, q.lo), math.min(p.hi, q.hi)
            if hi - lo > 1e-9 then
              add(p.index, q.index, lo == -math.huge and thickness * hi - cos * (outer ^ 2 - inner ^ 2) / 2
                                                      or thickness * (hi - lo))
            end
          end
        end
      end
      -- Groin: "north" voussoir i (x < 0 for i <= N/2) meets "west" voussoir N + 1 - i.
      if i <= n / 2 then add(row[1].index, rows[left_of[web]][n + 1 - i][1].index) end
    end
    for c, i in ipairs{ 1, n } do
      for _, p in ipairs(rows[web][i]) do add(p.index, s:find("support " .. springing[web][c])) end
    end
  end
  local count = 0
  for _ in pairs(expected) do count = count + 1 end
  local interfaces = s:interfaces()
  assert.equal(count, #interfaces)
  local springings = {}
  for _, f in ipairs(interfaces) do
    local key = math.min(f.a, f.b) .. "-" .. math.max(f.a, f.b)
    local area = expected[key]
    assert.is_truthy(area, "spurious contact " .. s:name(f.a) .. " / " .. s:name(f.b))
    expected[key] = nil
    assert.is_true(f.area > 1e-3, "degenerate contact " .. s:name(f.a) .. " / " .. s:name(f.b))
    if area ~= true then near(f.area, area, 1e-12, "contact area " .. s:name(f.a) .. " / " .. s:name(f.b)) end
    if s:is_support(f.a) or s:is_support(f.b) then
      near(math.abs(f.normal[3]), 1, 1e-15, "springing normal")
      local web = s:name(math.min(f.a, f.b)):match("^%a+")
      local key = web .. " " .. s:name(math.max(f.a, f.b))
      springings[key] = (springings[key] or 0) + f.area
    end
  end
  assert.is_nil(next(expected))
  -- Springing faces: together, trapezoids from the groin to the face.
  local length = (half - inner) + (half - inner - thickness)
  local sides = 0
  for _, area in pairs(springings) do
    near(area, thickness * length / 2, 1e-12, "springing area")
    sides = sides + 1
  end
  assert.equal(8, sides)
  return count
end

describe("models.groin_vault", function()
  local radius, thickness, voussoirs = 3, 0.6, 22
  local side = 2 * (radius + thickness)
  local s = groin_vault()
  local running = groin_vault{ bond = "running" }

  it("has four webs of voussoir rows cut into courses, then four corner supports", function()
    -- Pieces per row from the springing on the left to the right, at the
    -- defaults: the rows are shorter towards the springings.
    local counts = { stacked = { 1, 1, 1, 1, 1, 1, 2, 2, 3, 3, 4, 4, 3, 3, 2, 2, 1, 1, 1, 1, 1, 1 },
                     running = { 1, 1, 1, 1, 1, 2, 2, 3, 3, 4, 4, 4, 4, 3, 3, 2, 2, 1, 1, 1, 1, 1 } }
    for bond, vault in pairs{ stacked = s, running = running } do
      local index = 0
      for _, web in ipairs(webs) do
        for i = 1, voussoirs do
          for c = 1, counts[bond][i] do
            index = index + 1
            assert.equal(("%s voussoir %d course %d"):format(web, i, c), vault:name(index))
            assert.is_false(vault:is_support(index))
          end
        end
      end
      assert.equal(bond == "stacked" and 160 or 184, index)
      assert.equal(index + 4, #vault)
      for k, corner in ipairs{ "northwest", "southwest", "southeast", "northeast" } do
        assert.equal(index + k, vault:find("support " .. corner))
        assert.is_true(vault:is_support(index + k))
      end
    end
  end)

  it("has exactly the contacts of the topology, stacked and in running bond", function()
    assert.equal(292, check_topology(s, {}))
    assert.equal(412, check_topology(running, { bond = "running" }))
    -- One course: one block per voussoir and web.
    local one = groin_vault{ courses = 1 }
    assert.equal(4 * voussoirs + 4, #one)
    assert.equal(4 * (voussoirs - 1) + 2 * voussoirs + 8, check_topology(one, { courses = 1 }))
  end)

  it("has the volume of its polyhedral shape, converging to the groin vault's", function()
    local expected = polyhedral_volume(radius, thickness, voussoirs, side)
    near(support.free_volume(s), expected, 1e-12 * expected)
    near(support.free_volume(running), expected, 1e-12 * expected)
    near(support.free_volume(groin_vault{ courses = 1 }), expected, 1e-12 * expected)
    local exact = exact_volume(radius, thickness, side)
    local previous
    for _, n in ipairs{ 8, 16, 32, 64 } do
      local v = support.free_volume(groin_vault{ voussoirs = n, courses = 1 })
      near(v, polyhedral_volume(radius, thickness, n, side), 1e-12 * v)
      local error = exact - v
      assert.is_true(error > 0, "chords lie inside the circles")
      if previous then
        -- Second order: halving the step divides the error by about 4.
        local ratio = previous / error
        assert.is_true(ratio > 3.9 and ratio < 4.1, "convergence ratio " .. ratio)
      end
      previous = error
    end
    assert.is_true(previous / exact < 2e-3)
  end)

  it("keeps its topology and volume for other sizes, counts and bonds", function()
    for _, o in ipairs{ { voussoirs = 2 }, { voussoirs = 2, courses = 3, bond = "running" },
                        { voussoirs = 6, side = 8, bond = "running" }, { voussoirs = 8, courses = 1, bond = "running" },
                        { radius = 5, thickness = 1.2, voussoirs = 10, courses = 7 },
                        { voussoirs = 12, courses = 9, bond = "running" } } do
      local r, t = o.radius or radius, o.thickness or thickness
      local w = o.side or 2 * (r + t)
      local v = groin_vault(o)
      check_topology(v, o)
      local expected = polyhedral_volume(r, t, o.voussoirs, w)
      near(support.free_volume(v), expected, 1e-12 * expected)
    end
  end)

  it("is invariant under the square's symmetries", function()
    local maps = {
      function(x, y) return -y, x end, function(x, y) return -x, -y end, function(x, y) return y, -x end,
      function(x, y) return -x, y end, function(x, y) return x, -y end,
      function(x, y) return y, x end, function(x, y) return -y, -x end,
    }
    for _, vault in ipairs{ s, running } do
      local centroids, volumes = {}, {}
      for i = 1, #vault do centroids[i], volumes[i] = vault:block(i):centroid(), vault:block(i):volume() end
      for m, map in ipairs(maps) do
        for i = 1, #vault do
          local c = centroids[i]
          local x, y = map(c[1], c[2])
          local found = false
          for j = 1, #vault do
            local d = centroids[j]
            if math.abs(d[1] - x) < 1e-12 and math.abs(d[2] - y) < 1e-12 and math.abs(d[3] - c[3]) < 1e-12
               and math.abs(volumes[j] - volumes[i]) < 1e-12
               and vault:is_support(i) == vault:is_support(j) then
              found = true
              break
            end
          end
          assert.is_true(found, ("symmetry %d: no image of %s"):format(m, vault:name(i)))
        end
      end
      local lo, hi = vault:bounds()
      near(lo[1], -side / 2, 1e-15); near(hi[1], side / 2, 1e-15)
      near(lo[2], -side / 2, 1e-15); near(hi[2], side / 2, 1e-15)
      near(hi[3], radius + thickness / 2, 1e-12)
    end
  end)

  it("stands when ample and falls when thin, for both bonds", function()
    for _, bond in ipairs{ "stacked", "running" } do
      -- Running bond's solve may end "inaccurate"; its forces are tension-free.
      local ample = ashlar.analyze(groin_vault{ thickness = 0.6, bond = bond }, { friction = 0.7 })
      assert.is_true(ample.status == "converged" or ample.status == "inaccurate", ample.status)
      assert.is_true(ample.stable, bond)
      assert.equal(0, ample.infeasibility)
      local thin = ashlar.analyze(groin_vault{ thickness = 0.3, bond = bond }, { friction = 0.7 })
      assert.is_false(thin.stable, bond)
      assert.is_true(thin.infeasibility > 1e-3)
    end
  end)

  it("rejects bad options, naming models.groin_vault", function()
    expect_error({ "models.groin_vault: unknown option 'length'", "allowed:" }, groin_vault, { length = 3 })
    expect_error({ "models.groin_vault: voussoirs: a groin vault needs an even count", "got 15" }, groin_vault,
      { voussoirs = 15 })
    expect_error({ "models.groin_vault: voussoirs: must be >= 2, got 0" }, groin_vault, { voussoirs = 0 })
    expect_error({ "models.groin_vault: courses: must be >= 1, got 0" }, groin_vault, { courses = 0 })
    expect_error({ "models.groin_vault: courses: expected an integer, got 2.5" }, groin_vault, { courses = 2.5 })
    expect_error({ "models.groin_vault: bond: 'flemish' is not one of stacked, running" }, groin_vault,
      { bond = "flemish" })
    expect_error({ "models.groin_vault: bond: expected a string, got number" }, groin_vault, { bond = 1 })
    expect_error({ "models.groin_vault: thickness must be < 2 * radius (6), got 6" }, groin_vault,
      { thickness = 6 })
    expect_error({ "models.groin_vault: side must be > 2 * (radius + thickness / 2) (6.6), got 6.6" },
      groin_vault, { side = 6.6 })
    expect_error({ "models.groin_vault: side: must be > 0" }, groin_vault, { side = -1 })
    expect_error({ "models.groin_vault: radius: expected a finite number" }, groin_vault, { radius = 1 / 0 })
  end)
end)
