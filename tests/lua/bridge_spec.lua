-- models.cable_stayed_bridge (the thesis's figure 3): block and cable counts,
-- names and supports, every contact the construction implies (whole shared
-- faces between free blocks, which the optimiser needs), cable ends on block
-- vertices, horizontal walkway tops, symmetry about x = 0, option errors,
-- and the equilibrium: unstable as given, less and less infeasible as the
-- walkway gets lighter.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_generator_error

local function sub(a, b) return { a[1] - b[1], a[2] - b[2], a[3] - b[3] } end
local function cross(a, b)
  return { a[2] * b[3] - a[3] * b[2], a[3] * b[1] - a[1] * b[3], a[1] * b[2] - a[2] * b[1] }
end
local function norm(a) return math.sqrt(a[1] ^ 2 + a[2] ^ 2 + a[3] ^ 2) end

-- Vector area of a polygon (its normal times its area).
local function vector_area(points)
  local sum = { 0, 0, 0 }
  for i = 1, #points do
    local c = cross(points[i], points[i % #points + 1])
    for k = 1, 3 do sum[k] = sum[k] + c[k] / 2 end
  end
  return sum
end

local function face_points(block, face)
  local vertices, points = block:vertices(), {}
  for i, k in ipairs(face) do points[i] = vertices[k] end
  return points
end

-- Exactly (tolerance 0: cable ends) or within a tolerance (contact
-- polygons, which are computed).
local function is_vertex(block, point, tolerance)
  for _, v in ipairs(block:vertices()) do
    if norm(sub(v, point)) <= (tolerance or 0) then return true end
  end
  return false
end

-- The expected contacts as a set of "name|name" pairs (sorted names).
local function expected_pairs(N, M)
  local set = {}
  local function add(a, b)
    if a > b then a, b = b, a end
    set[a .. "|" .. b] = true
  end
  for k = 1, N - 1 do add(("arch voussoir %d"):format(k), ("arch voussoir %d"):format(k + 1)) end
  add("arch voussoir 1", "arch support left")
  add(("arch voussoir %d"):format(N), "arch support right")
  for k = 1, M - 1 do add(("deck %d"):format(k), ("deck %d"):format(k + 1)) end
  add("deck 1", "deck support left")
  add(("deck %d"):format(M), "deck support right")
  return set
end

local function check_topology(s, N, M)
  local expected, found, count = expected_pairs(N, M), {}, 0
  for _, f in ipairs(s:interfaces()) do
    local a, b = s:name(f.a), s:name(f.b)
    if a > b then a, b = b, a end
    local key = a .. "|" .. b
    assert(not found[key], "two interfaces between " .. key)
    assert(expected[key], "spurious contact " .. key)
    found[key] = f
    count = count + 1
  end
  for key in pairs(expected) do assert(found[key], "missing contact " .. key) end
  return found, count
end

describe("models.cable_stayed_bridge (defaults)", function()
  local s = models.cable_stayed_bridge()

  it("has 10 voussoirs, 10 walkway blocks, 4 supports and 8 cables, named in order", function()
    assert.equal(24, #s)
    for k = 1, 10 do
      assert.equal(k, s:find(("arch voussoir %d"):format(k)))
      assert.equal(10 + k, s:find(("deck %d"):format(k)))
    end
    assert.equal(21, s:find("arch support left")); assert.equal(22, s:find("arch support right"))
    assert.equal(23, s:find("deck support left")); assert.equal(24, s:find("deck support right"))
    for i = 1, #s do assert.equal(i > 20, s:is_support(i)) end
    -- Left to right along both arches.
    for i = 2, 10 do
      assert.is_true(s:block(i):centroid()[1] > s:block(i - 1):centroid()[1])
      assert.is_true(s:block(10 + i):centroid()[1] > s:block(9 + i):centroid()[1])
    end
    local cables = s:cables()
    assert.equal(8, #cables)
    for c, cable in ipairs(cables) do
      assert.equal(("deck %d"):format(c + 1), s:name(cable.from.block))
      assert.truthy(s:name(cable.to.block):match("^arch voussoir %d+$"))
      assert.equal(0, cable.mass_per_length)
    end
  end)

  it("has exactly the contacts of the construction, whole shared faces between free blocks", function()
    local found, count = check_topology(s, 10, 10)
    assert.equal(22, count)
    for key, f in pairs(found) do
      local a, b = f.a, f.b
      if not s:is_support(a) and not s:is_support(b) then
        -- The contact is a face of each block, vertex for vertex (no T-junctions).
        for _, i in ipairs{ a, b } do
          for _, v in ipairs(f.vertices) do
            assert(is_vertex(s:block(i), v, 1e-9), key .. ": a contact vertex is not a vertex of " .. s:name(i))
          end
        end
        assert.equal(4, #f.vertices)
        near(f.area, norm(vector_area(f.vertices)), 1e-9, key)
      end
    end
  end)

  it("hangs each walkway block from an inner top vertex to an arch intrados vertex on the walkway's side", function()
    local top, r_in = 1 + 0.6, 6 - 0.8 / 2
    for c, cable in ipairs(s:cables()) do
      local from, to = cable.from.point, cable.to.point
      assert(is_vertex(s:block(cable.from.block), from), "cable " .. c .. ": from is not a vertex of its block")
      assert(is_vertex(s:block(cable.to.block), to), "cable " .. c .. ": to is not a vertex of its block")
      assert.equal(top, from[3])
      near(to[2], -0.3, 0, "cable " .. c .. " on the walkway's face of the arch")
      near(math.sqrt(to[1] ^ 2 + to[3] ^ 2), r_in, 1e-12, "cable " .. c .. " at the intrados")
      -- On the inner edge of the walkway (towards the arch) and the nearer
      -- half: the arch vertex is on the same side of x = 0.
      assert.is_true(from[1] * to[1] > 0)
      assert.is_true(to[3] > top)
      near(cable.length, norm(sub(to, from)), 1e-12)
    end
  end)

  it("has a horizontal top face on every walkway block, at deck_height + deck_depth", function()
    for k = 1, 10 do
      local block = s:block(("deck %d"):format(k))
      local tops = 0
      for _, face in ipairs(block:faces()) do
        local points = face_points(block, face)
        local area = vector_area(points)
        if area[3] > 0 and math.abs(area[1]) + math.abs(area[2]) < 1e-12 then
          tops = tops + 1
          for _, p in ipairs(points) do assert.equal(1.6, p[3]) end
        end
      end
      assert.equal(1, tops, "deck " .. k)
    end
  end)

  it("has the closed-form polyhedral volumes", function()
    -- A loft between two radial joints: a sector's chord polygon, times the depth.
    local ri, ro = 6 - 0.4, 6 + 0.4
    for k = 1, 10 do
      near(s:block(k):volume(), 0.5 * (ro ^ 2 - ri ^ 2) * math.sin(math.pi / 10) * 0.6, 1e-12, "voussoir " .. k)
    end
    local rp = (4.5 ^ 2 + 3 ^ 2) / (2 * 3)
    local angle = 2 * math.asin(4.5 / rp) / 10
    for k = 1, 10 do
      near(s:block(10 + k):volume(), 0.5 * ((rp + 0.3) ^ 2 - (rp - 0.3) ^ 2) * math.sin(angle) * 0.6, 1e-12,
        "deck " .. k)
    end
  end)

  it("is symmetric about x = 0, vertex for vertex", function()
    local function mirror(name)
      local kind, k = name:match("^(.-) (%d+)$")
      if kind == "arch voussoir" or kind == "deck" then return ("%s %d"):format(kind, 11 - k) end
      return name:gsub("left", "LEFT"):gsub("right", "left"):gsub("LEFT", "right")
    end
    for i = 1, #s do
      local a, b = s:block(i), s:block(mirror(s:name(i)))
      for _, v in ipairs(a:vertices()) do
        assert(is_vertex(b, { -v[1], v[2], v[3] }), s:name(i) .. ": no mirror vertex")
      end
    end
  end)

  it("passes the walkway under the arch and the cables up to it", function()
    local lo, hi = s:bounds()
    near(lo[3], -0.8, 1e-12, "arch supports' bottom")
    near(hi[3], 6.4, 1e-12, "extrados crown")
    near(lo[2], -3.3, 1e-12, "walkway's outer edge at mid-span")
    for k = 1, 10 do
      for _, v in ipairs(s:block(("deck %d"):format(k)):vertices()) do
        assert.is_true(v[1] ^ 2 + v[3] ^ 2 < 5.6 ^ 2)
      end
    end
  end)
end)

describe("models.cable_stayed_bridge (options)", function()
  it("follows the counts", function()
    local s = models.cable_stayed_bridge{ arch_voussoirs = 7, deck_blocks = 6, cable_mass = 5 }
    assert.equal(7 + 6 + 4, #s)
    check_topology(s, 7, 6)
    assert.equal(4, #s:cables())
    for c, cable in ipairs(s:cables()) do
      assert.equal(("deck %d"):format(c + 1), s:name(cable.from.block))
      assert(is_vertex(s:block(cable.to.block), cable.to.point))
      assert.equal(5, cable.mass_per_length)
    end
    assert.equal(2, #models.cable_stayed_bridge{ deck_blocks = 4 }:cables())
  end)

  it("gives the arch and the walkway their densities", function()
    local s = models.cable_stayed_bridge{ density = 2000, deck_density = 500 }
    assert.equal(2000, s:block("arch voussoir 1"):density())
    assert.equal(500, s:block("deck 1"):density())
  end)

  it("rejects bad options, naming the generator and what is allowed", function()
    local f = models.cable_stayed_bridge
    expect_error({ "models.cable_stayed_bridge: unknown option 'radius' (allowed: arch_depth, arch_radius,",
                   "deck_density", "span" }, f, { radius = 5 })
    expect_error({ "models.cable_stayed_bridge: expected an option table, got number" }, f, 3)
    expect_error({ "models.cable_stayed_bridge: arch_radius: expected a number, got string" }, f, { arch_radius = "6" })
    expect_error({ "models.cable_stayed_bridge: arch_voussoirs: must be >= 2, got 1" }, f, { arch_voussoirs = 1 })
    expect_error({ "models.cable_stayed_bridge: deck_blocks: expected an integer, got 6.5" }, f, { deck_blocks = 6.5 })
    expect_error({ "models.cable_stayed_bridge: deck_blocks: must be >= 4, got 2" }, f, { deck_blocks = 2 })
    expect_error({ "models.cable_stayed_bridge: deck_blocks: expected an even count (both halves alike), got 7" },
                 f, { deck_blocks = 7 })
    expect_error({ "models.cable_stayed_bridge: deck_density: must be > 0, got 0" }, f, { deck_density = 0 })
    expect_error({ "models.cable_stayed_bridge: deck_height: must be >= 0, got -1" }, f, { deck_height = -1 })
    expect_error({ "models.cable_stayed_bridge: cable_mass: expected a finite number" }, f, { cable_mass = 0 / 0 })
    expect_error({ "models.cable_stayed_bridge: arch_thickness must be < 2 * arch_radius (12), got 12" },
                 f, { arch_thickness = 12 })
    expect_error({ "models.cable_stayed_bridge: deck_rise must be < span / 2 (4.5)" }, f, { deck_rise = 4.5 })
    expect_error({ "models.cable_stayed_bridge: deck_width must be < 2 * the walkway's radius in plan" },
                 f, { deck_rise = 0.5, span = 2, deck_width = 3 })
    expect_error({ "models.cable_stayed_bridge: the walkway and its supports", "must pass under the arch's intrados" },
                 f, { deck_height = 5 })
    expect_error({ "must pass under the arch's intrados (radius 5.6)" }, f, { span = 11, deck_rise = 4 })
  end)
end)

describe("models.cable_stayed_bridge (equilibrium, friction 0.7)", function()
  it("is unstable as given: the walkway is too heavy for the arch", function()
    local r = ashlar.analyze(models.cable_stayed_bridge())
    assert.is_false(r.stable)
    assert.is_true(r.infeasibility > 0.1, "infeasibility " .. r.infeasibility)
  end)

  it("is less infeasible as the walkway gets lighter, and stands at a tenth of its density", function()
    local last = math.huge
    for _, density in ipairs{ 2400, 1200, 900 } do
      local r = ashlar.analyze(models.cable_stayed_bridge{ deck_density = density })
      assert.is_false(r.stable)
      assert.is_true(r.infeasibility < last, "deck_density " .. density)
      last = r.infeasibility
    end
    for _, density in ipairs{ 600, 240 } do
      local r = ashlar.analyze(models.cable_stayed_bridge{ deck_density = density })
      assert.is_true(r.stable, "deck_density " .. density)
      assert.equal(0, r.infeasibility)
    end
  end)

  it("is nearly stable with a deeper arch: the cables mostly pull the arch over", function()
    assert.is_true(ashlar.analyze(models.cable_stayed_bridge{ arch_depth = 1 }).infeasibility < 0.01)
  end)
end)
