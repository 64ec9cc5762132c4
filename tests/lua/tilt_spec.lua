-- ashlar.tilt, the tilt-table test: a block on a tilted table tips at
-- atan(b/h) and slides at atan(mu), the sign convention (a positive angle
-- about +y acts as a body force along +x), and what a tilted copy keeps.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local expect_error, near = support.expect_error, support.near

local NO_SLIDING = { friction = math.huge }

-- A block b wide (x) and h high standing on a support slab (the table).
local function block_on_table(b, h)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { b, 0.8, h }, center = { 0, 0, h / 2 } }, { name = "block" })
  s:add(ashlar.box{ size = { 2, 1.5, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "table" })
  return s
end

local function stands_tilted(s, angle, options)
  return ashlar.analyze(ashlar.tilt(s, angle), options).stable
end

describe("tilt", function()
  it("tips a block over at atan(b/h) without sliding, either way", function()
    local b, h = 0.4, 1.0
    local s = block_on_table(b, h)
    local tipping = math.atan(b / h)
    for _, sign in ipairs{ 1, -1 } do
      assert.is_true(stands_tilted(s, sign * (tipping - 1e-3), NO_SLIDING))
      assert.is_false(stands_tilted(s, sign * (tipping + 1e-3), NO_SLIDING))
    end
  end)

  it("slides a block at atan(mu) when mu < b/h", function()
    local s = block_on_table(0.6, 1.0)
    for _, mu in ipairs{ 0.3, 0.5 } do
      local sliding = math.atan(mu)
      assert.is_true(stands_tilted(s, sliding - 1e-3, { friction = mu }))
      assert.is_false(stands_tilted(s, sliding + 1e-3, { friction = mu }))
      -- Without sliding it still stands there: it is friction that gives.
      assert.is_true(stands_tilted(s, sliding + 1e-3, NO_SLIDING))
    end
  end)

  it("acts, for a positive angle about +y, as a body force tan(angle) times the weight along +x", function()
    -- Two blocks, the top one shifted 0.45 along +x: tilted towards +x the
    -- top block tips at tan(angle) = (0.5 - 0.45) / 0.25 = 0.2; tilted the
    -- other way it takes far more.
    local s = models.stack{ blocks = 2, offset = 0.45 }
    local tipping = math.atan(0.2)
    assert.is_true(stands_tilted(s, tipping - 1e-3, NO_SLIDING))
    assert.is_false(stands_tilted(s, tipping + 1e-3, NO_SLIDING))
    assert.is_true(stands_tilted(s, -(tipping + 0.2), NO_SLIDING))
    -- The same verdicts from horizontal loads of tan(angle) times each
    -- block's weight at its centroid, untilted.
    local function stands_pushed(factor)
      local pushed = support.push_laterally(models.stack{ blocks = 2, offset = 0.45 }, factor)
      return ashlar.analyze(pushed, NO_SLIDING).stable
    end
    assert.is_true(stands_pushed(math.tan(tipping - 1e-3)))
    assert.is_false(stands_pushed(math.tan(tipping + 1e-3)))
  end)

  it("keeps a 24-voussoir semicircular arch standing at 0.01 rad, not at 0.5", function()
    local arch = models.arch{ radius = 5, thickness = 0.6, voussoirs = 24 }
    assert.is_true(stands_tilted(arch, 0.01, NO_SLIDING))
    assert.is_true(stands_tilted(arch, -0.01, NO_SLIDING))
    assert.is_false(stands_tilted(arch, 0.5, NO_SLIDING))
  end)

  it("turns about the centre of the bounding box's bottom by default, or about axis and origin", function()
    local s = block_on_table(0.4, 1.0)  -- spans x -1..1, y -0.75..0.75, z -0.2..1
    local angle = 0.3
    local c, sn = math.cos(angle), math.sin(angle)
    -- The block's corner (0.2, -0.4, 1) about the y axis through (0, 0, -0.2);
    -- blocks keep their vertex order.
    local corner
    for k, p in ipairs(s:block(1):vertices()) do
      if p[1] == 0.2 and p[2] == -0.4 and p[3] == 1 then corner = k end
    end
    local function corner_of(t) return t:block(1):vertices()[corner] end
    local dx, dz = 0.2, 1.2
    local tilted = ashlar.tilt(s, angle)
    local moved = ashlar.tilt(s, angle, { axis = { 0, 1, 0 }, origin = { 0, 0, -0.2 } })
    for _, t in ipairs{ tilted, moved } do
      local p = corner_of(t)
      near(p[1], c * dx + sn * dz, 1e-12, "x"); near(p[2], -0.4, 1e-12, "y"); near(p[3], -0.2 - sn * dx + c * dz, 1e-12, "z")
    end
    -- About x through the origin: y turns towards z.
    local about_x = ashlar.tilt(s, math.pi / 2, { axis = { 2, 0, 0 }, origin = { 0, 0, 0 } })
    local lo, hi = about_x:bounds()
    near(lo[2], -1, 1e-12, "y low"); near(hi[2], 0.2, 1e-12, "y high")
    near(lo[3], -0.75, 1e-12, "z low"); near(hi[3], 0.75, 1e-12, "z high")
  end)

  it("returns a new structure: names, supports, loads (still vertical) and cables carried over, the input unchanged", function()
    local s = block_on_table(0.4, 1.0)
    s:add_load{ block = "block", force = { 0, 0, -500 }, at = { 0.1, 0, 1 } }
    s:add_cable{ from = { block = "table", point = { -1, 0, 0 } }, to = { block = "block", point = { -0.2, 0, 1 } },
                 mass_per_length = 3, max_tension = 1e5 }
    local before = s:block(1):vertices()
    local angle = 0.25
    local t = ashlar.tilt(s, angle)
    assert.are_not.equal(s, t)
    assert.are.same(before, s:block(1):vertices())
    assert.equal(#s, #t)
    for i = 1, #s do
      assert.equal(s:name(i), t:name(i))
      assert.equal(s:is_support(i), t:is_support(i))
      near(t:block(i):volume(), s:block(i):volume(), 1e-12)
    end
    -- Points turn about (0, 0, -0.2).
    local function turned(p)
      local x, z = p[1], p[3] + 0.2
      return { math.cos(angle) * x + math.sin(angle) * z, p[2], -0.2 - math.sin(angle) * x + math.cos(angle) * z }
    end
    local load = t:loads()[1]
    assert.equal(1, load.block)
    assert.are.same({ 0, 0, -500 }, load.force)
    for k = 1, 3 do near(load.at[k], turned{ 0.1, 0, 1 }[k], 1e-12) end
    local cable = t:cables()[1]
    assert.equal(2, cable.from.block); assert.equal(1, cable.to.block)
    assert.equal(3, cable.mass_per_length); assert.equal(1e5, cable.max_tension)
    for k = 1, 3 do
      near(cable.from.point[k], turned{ -1, 0, 0 }[k], 1e-12)
      near(cable.to.point[k], turned{ -0.2, 0, 1 }[k], 1e-12)
    end
    assert.is_false(t:is_planar())
  end)

  it("keeps a planar structure planar about y only", function()
    local arch = models.arch{ voussoirs = 8 }
    assert.is_true(arch:is_planar())
    assert.is_true(ashlar.tilt(arch, 0.1):is_planar())
    assert.is_true(ashlar.tilt(arch, 0.1, { axis = { 0, -2, 0 } }):is_planar())
    assert.is_false(ashlar.tilt(arch, 0.1, { axis = { 0, 1, 0.1 } }):is_planar())
    assert.is_false(ashlar.tilt(arch, 0.1, { axis = { 1, 0, 0 } }):is_planar())
    assert.is_true(arch:is_planar())
  end)

  it("rejects bad arguments", function()
    local s = block_on_table(0.4, 1.0)
    expect_error({ "angle", "expected a finite number, got nan" }, ashlar.tilt, s, 0 / 0)
    expect_error({ "angle", "expected a finite number, got inf" }, ashlar.tilt, s, math.huge)
    expect_error({ "angle", "expected a number, got no value" }, ashlar.tilt, s)
    expect_error({ "axis", "non-zero" }, ashlar.tilt, s, 0.1, { axis = { 0, 0, 0 } })
    expect_error({ "axis", "table of 3 numbers" }, ashlar.tilt, s, 0.1, { axis = 1 })
    expect_error({ "origin[2]", "finite" }, ashlar.tilt, s, 0.1, { origin = { 0, 0 / 0, 0 } })
    expect_error({ "unknown option 'center'", "axis, origin" }, ashlar.tilt, s, 0.1, { center = { 0, 0, 0 } })
    expect_error({ "Structure expected, got number" }, ashlar.tilt, 1, 0.1)
  end)
end)
