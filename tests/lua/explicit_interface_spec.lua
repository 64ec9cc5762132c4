-- Explicit interfaces (s:add_interface): contacts that detection cannot find,
-- given as polygons. A block lifted 2 mm off a cylindrical bed has no
-- detected contact; its curved bottom given as the contact carries it with
-- the equilibrium of a block in a cylindrical groove, and the interfaces
-- survive saving, loading and tilting.
local ashlar = require "ashlar"
local support = require "spec_support"

local R, ALPHA, L = 1.0, math.rad(30), 1.0  -- radius, half-angle of the arc, length (m)
local FACETS, GAP = 18, 0.002

-- Points of the arc below the axis (0, *, R) lifted by `lift`, in n facets.
local function arc(n, lift)
  local points = {}
  for k = 0, n do
    local t = -ALPHA + 2 * ALPHA * k / n
    points[#points + 1] = { R * math.sin(t), 0, R - R * math.cos(t) + lift }
  end
  return points
end

-- A 24-facet bed (support) and a block of height h whose bottom is the arc
-- in FACETS facets, lifted by `lift` (m, negative: sunk into the bed).
local function seated(h, lift)
  local s = ashlar.structure()
  local bed, outline = arc(24, 0), {}
  for k = #bed, 1, -1 do outline[#outline + 1] = bed[k] end
  outline[#outline + 1] = { bed[1][1], 0, -0.3 }
  outline[#outline + 1] = { bed[#bed][1], 0, -0.3 }
  s:add(ashlar.prism(outline, { 0, L, 0 }), { support = true, name = "bed" })
  local bottom = arc(FACETS, lift)
  outline = {}
  for k = 1, #bottom do outline[#outline + 1] = bottom[k] end
  outline[#outline + 1] = { bottom[#bottom][1], 0, h + lift }
  outline[#outline + 1] = { bottom[1][1], 0, h + lift }
  s:add(ashlar.prism(outline, { 0, L, 0 }), { name = "block" })
  return s, bottom
end

-- The block's bottom facets as polygons: the curved joint, given.
local function bed_polygons(bottom)
  local polygons = {}
  for k = 1, #bottom - 1 do
    local p, q = bottom[k], bottom[k + 1]
    polygons[k] = { p, q, { q[1], L, q[3] }, { p[1], L, p[3] } }
  end
  return polygons
end

local function given(h, lift)
  local s, bottom = seated(h, lift)
  assert.equal(FACETS, s:add_interface{ a = "bed", b = "block", polygons = bed_polygons(bottom) })
  return s
end

describe("an explicit interface", function()
  it("is listed with the detected ones, marked, with the polygons' exact area", function()
    local s = seated(0.6, GAP)
    assert.equal(0, #s:interfaces())  -- 2 mm gap: nothing detected
    s = given(0.6, GAP)
    local found, area = s:interfaces(), 0
    assert.equal(FACETS, #found)
    for _, c in ipairs(found) do
      assert.is_true(c.explicit)
      assert.equal(1, c.a)
      assert.equal(2, c.b)
      -- from the bed (a) into the block (b): upwards, towards the axis
      assert.is_true(c.normal[3] > 0.85)
      area = area + c.area
    end
    -- FACETS chords of the arc, each 2 R sin(ALPHA / FACETS) long.
    assert.near(FACETS * 2 * R * math.sin(ALPHA / FACETS) * L, area, 1e-12)
    -- A detected interface says so too.
    local plain = ashlar.structure()
    plain:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, -0.5 } }, { support = true })
    plain:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
    assert.is_false(plain:interfaces()[1].explicit)
  end)

  it("stands without friction under a push through the axis up to W tan(alpha - alpha / facets)", function()
    -- Frictionless forces are normal to the facets, which point at the
    -- axis: the block holds a push through the axis while the resultant's
    -- direction is within the facet normals, +-(ALPHA - ALPHA / FACETS).
    local critical = math.tan(ALPHA - ALPHA / FACETS)
    for _, case in ipairs{ { 0.95 * critical, true }, { 1.05 * critical, false } } do
      local s = given(1.2, GAP)
      local weight = 9.81 * s:block(2):mass()
      s:add_load{ block = 2, force = { case[1] * weight, 0, 0 }, at = { 0, L / 2, R + GAP } }
      local r = ashlar.analyze(s, { friction = 0 })
      assert.equal("converged", r.status)
      assert.equal(case[2], r.stable, ("P / W = %.4f"):format(case[1]))
    end
  end)

  it("carries the block's weight through its polygons", function()
    local s = given(0.6, GAP)
    local r = ashlar.analyze(s, { friction = 0.5 })
    assert.is_true(r.stable)
    local force, moment = support.statics(s, r)
    local weight = 9.81 * s:block(2):mass()
    assert(force <= 1e-6 * weight, ("force imbalance %g N of %g N"):format(force, weight))
    assert(moment <= 1e-6 * weight, ("moment imbalance %g N m"):format(moment))
  end)

  it("lets the pair it joins overlap", function()
    local s = seated(0.6, -0.003)  -- sunk 3 mm into the bed
    support.expect_error({ "overlap" }, ashlar.analyze, s, { friction = 0.5 })
    s = given(0.6, -0.003)
    assert.equal(0, #s:overlaps())
    assert.is_true(ashlar.analyze(s, { friction = 0.5 }).stable)
  end)

  it("replaces what detection finds between its two blocks", function()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, -0.5 } }, { support = true })
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
    assert.near(1, s:interfaces()[1].area, 1e-12)
    -- Only the middle strip of the joint carries: a narrower base.
    s:add_interface{ a = 2, b = 1, polygons = { { { -0.1, -0.5, 0 }, { 0.1, -0.5, 0 }, { 0.1, 0.5, 0 }, { -0.1, 0.5, 0 } } } }
    local found = s:interfaces()
    assert.equal(1, #found)
    assert.is_true(found[1].explicit)
    assert.near(0.2, found[1].area, 1e-12)
    assert.same({ 0, 0, 1 }, found[1].normal)  -- stored from block 1 into block 2
    -- Tipping about the strip's edge: a push P at height 1 m against the
    -- weight's arm 0.1 m, P = 0.1 W.
    local weight = 9.81 * s:block(2):mass()
    for _, case in ipairs{ { 0.095, true }, { 0.105, false } } do
      local t = ashlar.structure()
      t:add(s:block(1), { support = true })
      t:add(s:block(2))
      t:add_interface{ a = 1, b = 2, polygons = { found[1].vertices } }
      t:add_load{ block = 2, force = { case[1] * weight, 0, 0 }, at = { 0, 0, 1 } }
      assert.equal(case[2], ashlar.analyze(t, { friction = 10 }).stable, tostring(case[1]))
    end
  end)

  it("is kept by save and load, and turns with its blocks in a tilt", function()
    local s = given(0.6, GAP)
    local path = os.tmpname()
    s:save(path)
    local loaded = ashlar.load(path)
    os.remove(path)
    local before, after = s:interfaces(), loaded:interfaces()
    assert.equal(#before, #after)
    for k = 1, #before do
      assert.is_true(after[k].explicit)
      assert.near(before[k].area, after[k].area, 1e-15)
      for i = 1, 3 do assert.near(before[k].normal[i], after[k].normal[i], 1e-15) end
    end
    local r1 = ashlar.analyze(s, { friction = 0.5 })
    local r2 = ashlar.analyze(loaded, { friction = 0.5 })
    assert.near(r1.objective, r2.objective, 1e-12 * math.abs(r1.objective) + 1e-15)

    -- Tilted 10 degrees about y: a pure rotation of everything, so each
    -- interface keeps its area and its normal turns by the same rotation.
    local angle = math.rad(10)
    local tilted = ashlar.tilt(s, angle, { origin = { 0, 0, 0 } })
    local turned = tilted:interfaces()
    assert.equal(FACETS, #turned)
    for k = 1, FACETS do
      local n = before[k].normal
      assert.near(before[k].area, turned[k].area, 1e-12)
      assert.near(math.cos(angle) * n[1] + math.sin(angle) * n[3], turned[k].normal[1], 1e-12)
      assert.near(-math.sin(angle) * n[1] + math.cos(angle) * n[3], turned[k].normal[3], 1e-12)
    end
  end)

  it("is refused by the analyses that move or mesh the blocks", function()
    local s = given(0.6, GAP)
    for _, call in ipairs{ { "gradient", ashlar.gradient }, { "optimize", ashlar.optimize } } do
      support.expect_error({ call[1] .. ": the structure has 18 explicit interfaces", "block 1 ('bed')" },
        call[2], s, { friction = 0.5 })
    end
    local boxes = ashlar.structure()  -- hexahedra, which the FEA meshes
    boxes:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, -0.5 } }, { support = true })
    boxes:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
    boxes:add_interface{ a = 1, b = 2, polygons = { { { 0, 0, 0 }, { 0.5, 0, 0 }, { 0, 0.5, 0 } } } }
    support.expect_error({ "fea: the structure has 1 explicit interface (from" }, ashlar.fea, boxes)
  end)

  it("names what is wrong with a bad polygon", function()
    local s = seated(0.6, GAP)
    local square = { { -0.1, 0.1, 0 }, { 0.1, 0.1, 0 }, { 0.1, 0.9, 0 }, { -0.1, 0.9, 0 } }
    local add = function(t) return s:add_interface(t) end
    support.expect_error({ "b: index 3 is out of range" }, add, { a = 1, b = 3, polygons = { square } })
    support.expect_error({ "a and b are both block 2" }, add, { a = 2, b = 2, polygons = { square } })
    support.expect_error({ "expected a list of polygons, got a list of points" }, add,
      { a = 1, b = 2, polygons = square })
    support.expect_error({ "polygon 1", "expected at least 3 points, got 2" }, add,
      { a = 1, b = 2, polygons = { { square[1], square[2] } } })
    support.expect_error({ "polygon 2: not planar: point 1 is 0.0696 m off its plane (allowed: 0.000917 m" }, add,
      { a = 1, b = 2, polygons = { square, { square[1], square[2], { 0.1, 0.9, 0.4 }, square[4] } } })
    support.expect_error({ "polygon 1", "crosses itself" }, add,
      { a = 1, b = 2, polygons = { { square[1], square[3], square[2], { -0.1, 0.6, 0 } } } })
    support.expect_error({ "polygon 1", "enclose no area" }, add,
      { a = 1, b = 2, polygons = { { square[1], square[2], square[1] } } })
    support.expect_error({ "lies 4.7 m from block 1 ('bed')" }, add,
      { a = 1, b = 2, polygons = { { { 0, 0, -5 }, { 1, 0, -5 }, { 1, 1, -5 } } } })
    support.expect_error({ "degrees off perpendicular to the given normal" }, add,
      { a = 1, b = 2, polygons = { square }, normal = { 1, 0, 0 } })
    assert.equal(0, #s:interfaces())  -- nothing of a refused call was kept
  end)
end)
