-- models.buttressed_vault: blocks, names, supports, contacts implied by the
-- topology, exact volume, mirror symmetry and option errors. Its figure 6
-- claims are in weights_spec.lua.
local ashlar = require "ashlar"
local buttressed_vault = require "ashlar.models.buttressed_vault"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

-- Vault: N trapezoids of the half annulus; flyers: F trapezoids of a
-- quarter annulus each (straight chords); piers and buttresses: boxes.
local function expected_volume(o)
  local function annulus(radius, thickness, pieces, angle)
    local inner, outer = radius - thickness / 2, radius + thickness / 2
    return pieces * 0.5 * (outer ^ 2 - inner ^ 2) * math.sin(angle / pieces)
  end
  local flyer_centre = o.pier_height - o.flyer_drop - o.flyer_thickness / 2 - o.flyer_radius
  return (annulus(o.radius, o.thickness, o.voussoirs, math.pi)
          + 2 * annulus(o.flyer_radius, o.flyer_thickness, o.flyer_voussoirs, math.pi / 2)
          + 2 * o.pier_width * o.pier_height + 2 * o.buttress_width * flyer_centre) * o.depth
end

describe("models.buttressed_vault", function()
  local cases = {
    { radius = 4, thickness = 0.6, voussoirs = 15, pier_width = 2, pier_height = 14, pier_blocks = 1,
      flyer_radius = 3, flyer_thickness = 0.4, flyer_voussoirs = 6, flyer_drop = 0, buttress_width = 1.2,
      buttress_blocks = 1, depth = 1 },                                       -- the defaults
    { radius = 3, thickness = 0.5, voussoirs = 8, pier_width = 1.1, pier_height = 9, pier_blocks = 3,
      flyer_radius = 2, flyer_thickness = 0.3, flyer_voussoirs = 3, flyer_drop = 0.7, buttress_width = 0.9,
      buttress_blocks = 2, depth = 0.8 },
  }
  for k, o in ipairs(cases) do
    local s = k == 1 and buttressed_vault() or buttressed_vault(o)

    it(("case %d: blocks, names, supports and mirror symmetry"):format(k), function()
      assert.equal(o.voussoirs + 2 * (o.pier_blocks + o.flyer_voussoirs + o.buttress_blocks + 2), #s)
      for i = 1, o.voussoirs do assert.equal(("vault %d"):format(i), s:name(i)) end
      local supports = 0
      for i = 1, #s do
        if s:is_support(i) then
          supports = supports + 1
          assert.is_truthy(s:name(i):match("ground$"), s:name(i))
        end
      end
      assert.equal(4, supports)
      assert.is_true(s:is_planar())
      for _, side in ipairs{ "left", "right" } do
        for _, part in ipairs{ { "pier", o.pier_blocks }, { "flyer", o.flyer_voussoirs },
                               { "buttress", o.buttress_blocks } } do
          for i = 1, part[2] do
            local name = ("%s %s %d"):format(side, part[1], i)
            local mirror = s:find((name:gsub(side, side == "left" and "right" or "left")))
            local c, m = s:block(s:find(name)):centroid(), s:block(mirror):centroid()
            near(c[1], -m[1], 1e-12, name); near(c[3], m[3], 1e-12, name)
          end
        end
        -- Flyers from the pier outwards and downwards.
        for i = 2, o.flyer_voussoirs do
          local a = s:block(s:find(("%s flyer %d"):format(side, i - 1))):centroid()
          local b = s:block(s:find(("%s flyer %d"):format(side, i))):centroid()
          assert.is_true(math.abs(b[1]) > math.abs(a[1]) and b[3] < a[3])
        end
      end
    end)

    it(("case %d: exactly the contacts of the topology"):format(k), function()
      local contacts = {}
      local function add(a, b, area) contacts[#contacts + 1] = { a, b, area } end
      for i = 1, o.voussoirs - 1 do add(("vault %d"):format(i), ("vault %d"):format(i + 1), o.thickness * o.depth) end
      add("vault 1", ("left pier %d"):format(o.pier_blocks), o.thickness * o.depth)
      add(("vault %d"):format(o.voussoirs), ("right pier %d"):format(o.pier_blocks), o.thickness * o.depth)
      for _, side in ipairs{ "left", "right" } do
        for _, column in ipairs{ { "pier", o.pier_blocks, o.pier_width }, { "buttress", o.buttress_blocks, o.buttress_width } } do
          local name, blocks, width = column[1], column[2], column[3]
          for i = 1, blocks - 1 do
            add(("%s %s %d"):format(side, name, i), ("%s %s %d"):format(side, name, i + 1), width * o.depth)
          end
          add(("%s %s 1"):format(side, name), ("%s %s ground"):format(side, name), width * o.depth)
        end
        local joint = o.flyer_thickness * o.depth
        -- The pier block that holds the flyer's crown joint.
        local crown_top = o.pier_height - o.flyer_drop
        local pier_block = math.min(o.pier_blocks, math.floor(crown_top / (o.pier_height / o.pier_blocks) - 1e-9) + 1)
        add(("%s pier %d"):format(side, pier_block), ("%s flyer 1"):format(side), joint)
        for i = 1, o.flyer_voussoirs - 1 do
          add(("%s flyer %d"):format(side, i), ("%s flyer %d"):format(side, i + 1), joint)
        end
        add(("%s flyer %d"):format(side, o.flyer_voussoirs), ("%s buttress %d"):format(side, o.buttress_blocks), joint)
      end
      support.expect_contacts(s, contacts)
    end)

    it(("case %d: volume of the polyhedral shape"):format(k), function()
      local volume = expected_volume(o)
      near(support.free_volume(s), volume, 1e-12 * volume)
      local lo, hi = s:bounds()
      near(lo[2], -o.depth / 2, 1e-15); near(hi[2], o.depth / 2, 1e-15)
    end)
  end

  it("stands at the defaults", function()
    local r = ashlar.analyze(buttressed_vault(), { tolerance = 1e-7 })
    assert.is_true(r.stable)
    assert.equal(0, r.infeasibility)
  end)

  it("rejects bad options, naming models.buttressed_vault", function()
    expect_error({ "models.buttressed_vault: unknown option 'buttres_width'", "allowed:" }, buttressed_vault,
      { buttres_width = 1 })
    expect_error({ "models.buttressed_vault: pier_width must be > thickness (0.6)", "got 0.5" }, buttressed_vault,
      { pier_width = 0.5 })
    expect_error({ "models.buttressed_vault: buttress_width must be > flyer_thickness (0.4)", "got 0.4" },
      buttressed_vault, { buttress_width = 0.4 })
    expect_error({ "models.buttressed_vault: flyer_thickness must be < 2 * flyer_radius (6), got 6" },
      buttressed_vault, { flyer_thickness = 6, buttress_width = 7 })
    expect_error({ "models.buttressed_vault: the flyer does not fit under the pier's top", "(3), got 3.2" },
      buttressed_vault, { pier_height = 3 })
    expect_error({ "models.buttressed_vault: buttress_blocks: expected an integer, got 1.5" }, buttressed_vault,
      { buttress_blocks = 1.5 })
    expect_error({ "models.buttressed_vault: thickness must be < 2 * radius (8), got 9" }, buttressed_vault,
      { thickness = 9, pier_width = 10 })
  end)
end)
