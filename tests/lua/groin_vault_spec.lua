-- models.groin_vault: blocks, contacts implied by the topology (radial
-- joints within the webs, groin joints between them, springings), the
-- volume of the polyhedral shape and its convergence to the circular
-- groin vault, the square's symmetries, option errors, and an ample vault
-- standing.
local ashlar = require "ashlar"
local groin_vault = require "ashlar.models.groin_vault"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

local webs = { "north", "west", "south", "east" }

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

describe("models.groin_vault", function()
  local radius, thickness, voussoirs = 3, 0.3, 16
  local side = 2 * (radius + thickness)
  local s = groin_vault()

  it("has four webs of voussoirs, then four corner supports", function()
    assert.equal(4 * voussoirs + 4, #s)
    for w, web in ipairs(webs) do
      for i = 1, voussoirs do
        local index = (w - 1) * voussoirs + i
        assert.equal(("%s voussoir %d"):format(web, i), s:name(index))
        assert.is_false(s:is_support(index))
      end
    end
    for k, corner in ipairs{ "northwest", "southwest", "southeast", "northeast" } do
      assert.equal(4 * voussoirs + k, s:find("support " .. corner))
      assert.is_true(s:is_support(4 * voussoirs + k))
    end
  end)

  it("has exactly the contacts of the topology", function()
    local half, inner = side / 2, radius - thickness / 2
    local expected = {}
    local function add(a, b, area)
      local i, j = s:find(a), s:find(b)
      expected[math.min(i, j) .. "-" .. math.max(i, j)] = area or true
    end
    -- Groins: the web on the left of a face meets the next web anticlockwise;
    -- "north" voussoir i (x < 0 for i <= N/2) meets "west" voussoir N + 1 - i.
    for w, web in ipairs(webs) do
      local left = webs[w % 4 + 1]
      for i = 1, voussoirs - 1 do add(("%s voussoir %d"):format(web, i), ("%s voussoir %d"):format(web, i + 1)) end
      for i = 1, voussoirs / 2 do
        add(("%s voussoir %d"):format(web, i), ("%s voussoir %d"):format(left, voussoirs + 1 - i))
      end
    end
    local springing = { north = { "northwest", "northeast" }, west = { "southwest", "northwest" },
                        south = { "southeast", "southwest" }, east = { "northeast", "southeast" } }
    for web, corners in pairs(springing) do
      add(web .. " voussoir 1", "support " .. corners[1])
      add(("%s voussoir %d"):format(web, voussoirs), "support " .. corners[2])
    end
    local count = 0
    for _ in pairs(expected) do count = count + 1 end
    assert.equal(4 * (voussoirs - 1) + 2 * voussoirs + 8, count)
    local interfaces = s:interfaces()
    assert.equal(count, #interfaces)
    for _, f in ipairs(interfaces) do
      local key = math.min(f.a, f.b) .. "-" .. math.max(f.a, f.b)
      assert.is_truthy(expected[key], "spurious contact " .. s:name(f.a) .. " / " .. s:name(f.b))
      expected[key] = nil
      assert.is_true(f.area > 1e-3, "degenerate contact " .. s:name(f.a) .. " / " .. s:name(f.b))
    end
    assert.is_nil(next(expected))
    -- Springing faces: trapezoids from the groin to the face.
    for _, f in ipairs(interfaces) do
      if s:is_support(f.a) or s:is_support(f.b) then
        near(math.abs(f.normal[3]), 1, 1e-15, "springing normal")
        local length = (half - inner) + (half - inner - thickness)
        near(f.area, thickness * length / 2, 1e-12, "springing area")
      end
    end
  end)

  it("has the volume of its polyhedral shape, converging to the groin vault's", function()
    local expected = polyhedral_volume(radius, thickness, voussoirs, side)
    near(support.free_volume(s), expected, 1e-12 * expected)
    local exact = exact_volume(radius, thickness, side)
    local previous
    for _, n in ipairs{ 8, 16, 32, 64 } do
      local v = support.free_volume(groin_vault{ voussoirs = n })
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

  it("keeps its counts and volume for other sizes and counts", function()
    for _, o in ipairs{ { voussoirs = 2 }, { voussoirs = 6, side = 8 }, { radius = 5, thickness = 1.2, voussoirs = 10 } } do
      local r, t = o.radius or radius, o.thickness or thickness
      local w = o.side or 2 * (r + t)
      local v = groin_vault(o)
      assert.equal(4 * o.voussoirs + 4, #v)
      assert.equal(4 * (o.voussoirs - 1) + 2 * o.voussoirs + 8, #v:interfaces())
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
    for m, map in ipairs(maps) do
      for i = 1, #s do
        local c = s:block(i):centroid()
        local x, y = map(c[1], c[2])
        local found = false
        for j = 1, #s do
          local d = s:block(j):centroid()
          if math.abs(d[1] - x) < 1e-12 and math.abs(d[2] - y) < 1e-12 and math.abs(d[3] - c[3]) < 1e-12
             and math.abs(s:block(j):volume() - s:block(i):volume()) < 1e-12
             and s:is_support(i) == s:is_support(j) then
            found = true
            break
          end
        end
        assert.is_true(found, ("symmetry %d: no image of %s"):format(m, s:name(i)))
      end
    end
    local lo, hi = s:bounds()
    near(lo[1], -side / 2, 1e-15); near(hi[1], side / 2, 1e-15)
    near(lo[2], -side / 2, 1e-15); near(hi[2], side / 2, 1e-15)
    near(hi[3], radius + thickness / 2, 1e-12)
  end)

  it("stands when ample and falls when thin", function()
    local ample = ashlar.analyze(groin_vault{ thickness = 0.6 }, { friction = 0.7 })
    assert.equal("converged", ample.status)
    assert.is_true(ample.stable)
    assert.equal(0, ample.infeasibility)
    local thin = ashlar.analyze(groin_vault{ thickness = 0.3 }, { friction = 0.7 })
    assert.is_false(thin.stable)
    assert.is_true(thin.infeasibility > 1e-3)
  end)

  it("rejects bad options, naming models.groin_vault", function()
    expect_error({ "models.groin_vault: unknown option 'length'", "allowed:" }, groin_vault, { length = 3 })
    expect_error({ "models.groin_vault: voussoirs: a groin vault needs an even count", "got 15" }, groin_vault,
      { voussoirs = 15 })
    expect_error({ "models.groin_vault: voussoirs: must be >= 2, got 0" }, groin_vault, { voussoirs = 0 })
    expect_error({ "models.groin_vault: thickness must be < 2 * radius (6), got 6" }, groin_vault,
      { thickness = 6 })
    expect_error({ "models.groin_vault: side must be > 2 * (radius + thickness / 2) (6.3), got 6.3" },
      groin_vault, { side = 6.3 })
    expect_error({ "models.groin_vault: side: must be > 0" }, groin_vault, { side = -1 })
    expect_error({ "models.groin_vault: radius: expected a finite number" }, groin_vault, { radius = 1 / 0 })
  end)
end)
