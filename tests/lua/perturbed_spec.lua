-- Imperfect models (models.perturbed): a barrel vault and a thin dome whose
-- every free vertex is moved by up to 1 % of its block's size keep their
-- contacts (every pair of blocks, total area within 2 %) and their verdict,
-- thick and thin, once the contact tolerance covers the moves: most joints
-- are held twice, and their two copies meet on their mid-plane with the
-- joint's whole area. The vault comes back from an OBJ file (triangulated,
-- single precision), with `planarity`, as the same blocks with the same
-- faces and contacts, and from a COMPAS assembly with the same contacts.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local AMOUNT, PLANARITY = 0.01, 0.05

-- Block pairs in contact, total area, and how many interfaces are mid-plane ones.
local function contacts(s, tolerance, angle)
  local area, seen, pairs_found, mid_plane = 0, {}, 0, 0
  for _, c in ipairs(s:interfaces{ tolerance = tolerance, min_width = tolerance, angle = angle or math.rad(15) }) do
    area = area + c.area
    if c.mid_plane then mid_plane = mid_plane + 1 end
    local key = c.a .. "," .. c.b
    if not seen[key] then seen[key], pairs_found = true, pairs_found + 1 end
  end
  return pairs_found, area, mid_plane
end

local function mean_block_size(s)
  local sum = 0
  for i = 1, #s do
    local lo, hi = s:block(i):bounds()
    sum = sum + math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
  end
  return sum / #s
end

describe("a perturbed barrel vault through OBJ", function()
  local folder
  setup(function() folder = support.temp_folder() end)
  teardown(function() support.remove_folder(folder) end)

  for _, case in ipairs{ { thickness = 0.45, stable = true }, { thickness = 0.27, stable = false } } do
    it(("keeps its contacts and its verdict at t/R = %.2f"):format(case.thickness / 3), function()
      local s = models.barrel_vault{ radius = 3, thickness = case.thickness, voussoirs = 24, courses = 6,
                                     bond = "running" }
      local moved = models.perturbed(s, { amount = AMOUNT, planarity = PLANARITY, seed = 5 })
      local tolerance = 2.5 * AMOUNT * mean_block_size(s)
      local expected_pairs, expected_area, coincident = contacts(s)
      local found_pairs, found_area, mid_plane = contacts(moved, tolerance)
      assert.equal(expected_pairs, found_pairs)
      assert.near(expected_area, found_area, 0.02 * expected_area)
      -- The generated vault's joints coincide; the moved one's voussoir
      -- joints are pairs of copies (the bed joints under two staggered
      -- blocks are cut).
      assert.equal(0, coincident)
      assert.is_true(mid_plane > 0.3 * found_pairs)
      local r = ashlar.analyze(moved, { friction = 0.7, contact_tolerance = tolerance, contact_min_width = tolerance, contact_angle = math.rad(15) })
      assert.equal("converged", r.status)
      assert.equal(case.stable, r.stable)
      assert.equal(case.stable, ashlar.analyze(s, { friction = 0.7 }).stable)

      -- Through OBJ (single precision) and back with planarity: the same
      -- blocks, supports picked by name.
      local path = folder .. "/vault.obj"
      ashlar.export(moved, path)
      local supports = {}
      for i = 1, #s do if s:is_support(i) then supports[s:name(i)] = true end end
      local imported = ashlar.import(path, { planarity = PLANARITY, support = function(name) return supports[name] == true end })
      assert.equal(#s, #imported)
      for i = 1, #s do
        local j = imported:find(moved:name(i))
        assert.equal(moved:is_support(i), imported:is_support(j))
        -- The file's triangles are the warped quads again.
        assert.equal(#moved:block(i):faces(), #imported:block(j):faces())
        assert.near(moved:block(i):volume(), imported:block(j):volume(), 1e-6 * moved:block(i):volume())
        for k = 1, 3 do assert.near(moved:block(i):centroid()[k], imported:block(j):centroid()[k], 1e-6) end
      end
      local obj_pairs, obj_area, obj_mid_plane = contacts(imported, tolerance)
      assert.equal(found_pairs, obj_pairs)
      assert.equal(mid_plane, obj_mid_plane)
      assert.near(found_area, obj_area, 1e-5 * found_area)  -- single precision

      -- Through a COMPAS assembly (doubles, polygon faces) with contacts
      -- left to detection: the same blocks, supports from the file, and the
      -- same contacts and verdict as the moved vault in memory.
      local compas_path = folder .. "/vault.json"
      ashlar.export(moved, compas_path)
      local compas = ashlar.import(compas_path, { planarity = PLANARITY, interfaces = "detect" })
      assert.equal(#s, #compas)
      for i = 1, #s do
        assert.equal(moved:is_support(i), compas:is_support(i))
        assert.near(moved:block(i):volume(), compas:block(i):volume(), 1e-12 * moved:block(i):volume())
      end
      local compas_pairs, compas_area = contacts(compas, tolerance)
      assert.equal(found_pairs, compas_pairs)
      assert.near(found_area, compas_area, 1e-9 * found_area)
      local rc = ashlar.analyze(compas, { friction = 0.7, contact_tolerance = tolerance, contact_min_width = tolerance, contact_angle = math.rad(15) })
      assert.equal(case.stable, rc.stable)
    end)
  end

  it("is reproducible, and refuses what it cannot copy", function()
    local s = models.arch{}
    local a = models.perturbed(s, { seed = 2 }):block(5):vertices()
    local b = models.perturbed(s, { seed = 2 }):block(5):vertices()
    local c = models.perturbed(s, { seed = 3 }):block(5):vertices()
    assert.same(a, b)
    assert.are_not.same(a, c)
    -- Supports stay; every free vertex moves by at most amount x the block's size.
    local moved = models.perturbed(s, { amount = 0.02, seed = 4 })
    for i = 1, #s do
      local lo, hi = s:block(i):bounds()
      local size = math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
      local before, after = s:block(i):vertices(), moved:block(i):vertices()
      for k = 1, #before do
        local d = math.sqrt((after[k][1] - before[k][1]) ^ 2 + (after[k][2] - before[k][2]) ^ 2 +
                            (after[k][3] - before[k][3]) ^ 2)
        if s:is_support(i) then assert.equal(0, d) else assert.is_true(d <= 0.02 * size + 1e-12) end
      end
    end
    support.expect_error({ "models.perturbed", "expected a structure" }, models.perturbed, {})
    support.expect_error({ "models.perturbed", "amount", "<= 0.1" }, models.perturbed, s, { amount = 1 })
  end)
end)

-- The thin dome (t/R = 0.02) is the hard case: its joints are a twentieth
-- of its largest blocks' size, so the moves tilt their copies by up to
-- 2 atan(2 x 0.01 x size / thickness), 46 degrees, and cutting them would
-- lose a quarter of the area. As pairs of copies every joint is found, with
-- its area.
describe("a perturbed thin dome", function()
  it("keeps every contact, its area and its verdict", function()
    local s = models.dome{ radius = 5, thickness = 0.1 }
    local moved = models.perturbed(s, { amount = AMOUNT, planarity = PLANARITY, seed = 4 })
    local largest = 0
    for i = 1, #s do
      if not s:is_support(i) then
        local lo, hi = s:block(i):bounds()
        largest = math.max(largest, math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2))
      end
    end
    local angle = 2 * math.atan(2 * AMOUNT * largest / 0.1)
    local tolerance = 2.5 * AMOUNT * mean_block_size(s)
    local expected_pairs, expected_area = contacts(s)
    local found_pairs, found_area, mid_plane = contacts(moved, tolerance, angle)
    assert.equal(608, expected_pairs)
    assert.equal(expected_pairs, found_pairs)
    assert.near(expected_area, found_area, 0.02 * expected_area)
    assert.is_true(mid_plane > 0.5 * found_pairs)
    local r = ashlar.analyze(moved, { friction = 0.7, contact_tolerance = tolerance, contact_min_width = tolerance, contact_angle = angle })
    assert.equal("converged", r.status)
    assert.is_false(r.stable)
    assert.is_false(ashlar.analyze(s, { friction = 0.7 }).stable)
  end)
end)

describe("the margins of a perturbed dome", function()
  it("see the joints the analysis sees: contact_angle reaches their programs", function()
    -- An 8 x 4 dome moved by up to 3 %: at the default contact angle 54 of
    -- its 80 joints are found and blocks float; at 15 degrees 76, every
    -- block is held, and it stands from friction 0.6675 up (as an LP that
    -- shares no code with ashlar finds on the same contacts).
    local s = models.dome{ meridians = 8, parallels = 4 }
    local moved = models.perturbed(s, { amount = 0.03, seed = 3 })
    local tolerance = 2.5 * 0.03 * mean_block_size(s)
    local angle = math.rad(15)
    assert.equal(54, #moved:interfaces{ tolerance = tolerance, min_width = tolerance })
    assert.equal(76, #moved:interfaces{ tolerance = tolerance, min_width = tolerance, angle = angle })
    local held = { contact_tolerance = tolerance, contact_min_width = tolerance, contact_angle = angle, progress = false }
    local r = ashlar.analyze(moved, { friction = 100, contact_tolerance = tolerance, contact_min_width = tolerance, contact_angle = angle })
    assert.equal(0, #r.floating)
    assert.is_true(r.stable)
    local contact = { tolerance = tolerance, min_width = tolerance, angle = angle }
    assert.is_true(support.independent_verdict(moved, 100, contact))
    local demand = ashlar.friction_demand(moved, held)
    assert.equal("optimal", demand.status)
    support.near(demand.friction, 0.667533581, 1e-6, "friction demand")
    assert.is_false(support.independent_verdict(moved, 0.999 * demand.friction, contact))
    assert.is_true(support.independent_verdict(moved, 1.001 * demand.friction, contact))
    assert.equal("optimal", ashlar.load_factor(moved, held).status)
    local loose = { contact_tolerance = tolerance, contact_min_width = tolerance, progress = false }
    assert.is_true(#ashlar.analyze(moved, { contact_tolerance = tolerance, contact_min_width = tolerance }).floating > 0)
    assert.equal("floating", ashlar.friction_demand(moved, loose).status)
    assert.equal("floating", ashlar.load_factor(moved, loose).status)
  end)
end)
