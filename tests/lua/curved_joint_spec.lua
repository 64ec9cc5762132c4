-- A block seated on a cylindrical bed, the two faceted differently (as
-- meshes of one curved joint from two sources are): the contact is found as
-- many small interfaces whose total area is the bed's, and its frictionless
-- equilibrium matches the closed form of a block in a cylindrical groove.
local ashlar = require "ashlar"
local support = require "spec_support"

local R, ALPHA, L = 1.0, math.rad(30), 1.0  -- radius, half-angle of the arc, length (m)

-- Points of the arc below the axis (0, *, R), from -ALPHA to ALPHA.
local function arc(n)
  local points = {}
  for k = 0, n do
    local t = -ALPHA + 2 * ALPHA * k / n
    points[#points + 1] = { R * math.sin(t), 0, R - R * math.cos(t) }
  end
  return points
end

-- The bed (a support whose top is the arc in n_bed facets) and a block of
-- height h above the axis' foot whose bottom is the arc in n_block facets.
local function seated(n_bed, n_block, h)
  local s = ashlar.structure()
  local bed, outline = arc(n_bed), {}
  for k = #bed, 1, -1 do outline[#outline + 1] = bed[k] end
  outline[#outline + 1] = { bed[1][1], 0, -0.3 }
  outline[#outline + 1] = { bed[#bed][1], 0, -0.3 }
  s:add(ashlar.prism(outline, { 0, L, 0 }), { support = true })
  local bottom = arc(n_block)
  outline = {}
  for k = 1, #bottom do outline[#outline + 1] = bottom[k] end
  outline[#outline + 1] = { bottom[#bottom][1], 0, h }
  outline[#outline + 1] = { bottom[1][1], 0, h }
  s:add(ashlar.prism(outline, { 0, L, 0 }))
  return s
end

describe("a curved joint faceted differently on its two sides", function()
  local TOLERANCE = 1e-3  -- above the facets' sagitta (2e-4 m at 18 facets)

  it("is found as interfaces whose total area is the bed's", function()
    for _, facets in ipairs{ { 24, 18 }, { 30, 17 } } do
      local s = seated(facets[1], facets[2], 0.6)
      local area = 0
      for _, c in ipairs(s:interfaces{ tolerance = TOLERANCE }) do area = area + c.area end
      -- The exact bed: arc length 2 R ALPHA times L.
      assert.near(2 * R * ALPHA * L, area, 1e-3 * 2 * R * ALPHA * L)
      -- Below the sagitta the two facetings interpenetrate, by a sliver
      -- thinner than the sagitta, not by the joint's whole depth.
      local overlaps = s:overlaps{ tolerance = 1e-4 }
      assert.equal(1, #overlaps)
      assert.is_true(overlaps[1].depth < 5e-4, "depth " .. overlaps[1].depth)
    end
  end)

  it("stands without friction under a push through the axis up to W tan(alpha)", function()
    -- Without friction every contact force is normal to the bed, so passes
    -- through the cylinder's axis: a block in the groove carries a force
    -- through the axis while its direction lies within the facet normals,
    -- which span +-(ALPHA - ALPHA / 24) on the 24-facet bed: tan 28.75 deg
    -- = 0.5486 (tan 30 deg = 0.577 for the smooth bed).
    local critical = math.tan(ALPHA - ALPHA / 24)
    for _, case in ipairs{ { 0.95 * critical, true }, { 1.05 * critical, false } } do
      local s = seated(24, 18, 1.2)
      local weight = 9.81 * s:block(2):mass()
      s:add_load{ block = 2, force = { case[1] * weight, 0, 0 }, at = { 0, L / 2, R } }
      local r = ashlar.analyze(s, { friction = 0, contact_tolerance = TOLERANCE })
      assert.equal("converged", r.status)
      assert.equal(case[2], r.stable, ("P / W = %.4f"):format(case[1]))
    end
    -- A push at the block's centroid, 0.38 m below the axis, has a moment
    -- about it that normal forces through the axis cannot balance; a flat
    -- facet (0.044 m wide at 24) takes at most its weight share times half
    -- its width, well below 0.2 W x 0.38 m.
    local s = seated(24, 18, 1.2)
    local b = s:block(2)
    assert.near(0.62, b:centroid()[3], 0.01)
    s:add_load{ block = 2, force = { 0.2 * 9.81 * b:mass(), 0, 0 }, at = b:centroid() }
    assert.is_false(ashlar.analyze(s, { friction = 0, contact_tolerance = TOLERANCE }).stable)
  end)

  it("carries the block's weight", function()
    local s = seated(24, 18, 0.6)
    local r = ashlar.analyze(s, { friction = 0, contact_tolerance = TOLERANCE })
    assert.is_true(r.stable)
    local force, moment = support.statics(s, r, { tolerance = TOLERANCE })
    local weight = 9.81 * s:block(2):mass()
    assert(force <= 1e-6 * weight, ("force imbalance %g N of %g N"):format(force, weight))
    assert(moment <= 1e-6 * weight, ("moment imbalance %g N m"):format(moment))
  end)

  it("drops interfaces smaller than min_area", function()
    local s = seated(24, 18, 0.6)
    local all = s:interfaces{ tolerance = TOLERANCE }
    local smallest, largest = math.huge, 0
    for _, c in ipairs(all) do
      smallest, largest = math.min(smallest, c.area), math.max(largest, c.area)
    end
    local cut = 0.5 * (smallest + largest)
    local kept = s:interfaces{ tolerance = TOLERANCE, min_area = cut }
    local expected = 0
    for _, c in ipairs(all) do if c.area >= cut then expected = expected + 1 end end
    assert.is_true(expected > 0 and expected < #all)
    assert.equal(expected, #kept)
    for _, c in ipairs(kept) do assert.is_true(c.area >= cut) end
  end)
end)

describe("the contact angle", function()
  -- A block whose bottom is tilted 10 degrees from the ground it stands on:
  -- its faces are not opposite within the default 8.1 degrees.
  local function tilted()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 0.5, -0.1 } }, { support = true })
    local rise = math.tan(math.rad(10))
    s:add(ashlar.prism({ { -0.5, 0, 0 }, { 0.5, 0, rise }, { 0.5, 0, 1 }, { -0.5, 0, 1 } }, { 0, 1, 0 }))
    return s, rise
  end

  it("decides which nearly opposite faces may touch", function()
    local s, rise = tilted()
    assert.equal(0, #s:interfaces{ tolerance = 1.1 * rise })
    local found = s:interfaces{ tolerance = 1.1 * rise, angle = math.rad(12) }
    assert.equal(1, #found)
    -- The gap at every vertex of the contact polygon stays within the
    -- tolerance: below the rise, no contact at any angle.
    assert.equal(0, #s:interfaces{ tolerance = 0.5 * rise, angle = math.rad(12) })
  end)

  it("is refused outside (0, pi/2)", function()
    local s = tilted()
    support.expect_error({ "angle", "between 0 and pi/2", "got 2" }, s.interfaces, s, { angle = 2 })
    support.expect_error({ "contact_angle", "got 0" }, ashlar.analyze, s, { contact_angle = 0 })
  end)
end)
