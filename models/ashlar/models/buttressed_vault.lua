-- models.buttressed_vault: the cross-section of a vault held by flying
-- buttresses (Shin 2014, figure 6), in the x-z plane, depth along y centred
-- on y = 0, symmetric about x = 0:
--
--                      vault (semicircle)
--            flyer  /                      \  flyer
--   buttress  ---- pier                   pier ----  buttress
--   (blocks)       (blocks)               (blocks)   (blocks)
--   ground         ground                 ground     ground
--
-- The vault springs from the inner part of each pier's top (horizontal
-- springing joints). Each flyer is the outer half of a semicircular arch:
-- its crown joint is vertical and abuts the pier's outer face just below
-- the pier's top (`flyer_drop`), its springing joint is horizontal and
-- rests on the inner part of the buttress's top. Piers and buttresses are
-- columns of equal boxes on supports named "ground ...". The vault's
-- thrust pushes the piers outwards at their tops; the flyers carry it to
-- the buttresses, whose weight turns it down into the ground.
--
-- At the defaults (friction 0.7) only the buttresses' weights are needed:
-- any other block could be weightless and the rest would still stand, each
-- buttress needs 0.329 of its own (figure 6a). Split into 2 blocks, only
-- the top one needs weight (0.112); split into 3 or more, none does: the
-- answer depends on the discretisation, as the thesis says (figure 6b;
-- tests/lua/weights_spec.lua). Blocks: "vault 1".."vault N" (left to
-- right), "<side> flyer 1".."<side> flyer F" (from the pier outwards),
-- "<side> pier 1".."<side> pier P" and "<side> buttress 1".."<side>
-- buttress B" (from the bottom), side "left" or "right"; supports
-- "<side> pier ground", "<side> buttress ground". Every face is planar.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local semicircle = require "ashlar.models.semicircle"

local spec = {
  radius = { type = "number", default = 4, above = 0 },            -- m, vault centreline
  thickness = { type = "number", default = 0.6, above = 0 },       -- m, vault, radial
  voussoirs = { type = "number", default = 15, integer = true, min = 2 },  -- vault
  pier_width = { type = "number", default = 2, above = 0 },        -- m, along x (> thickness)
  pier_height = { type = "number", default = 14, above = 0 },      -- m, ground to vault springing
  pier_blocks = { type = "number", default = 1, integer = true, min = 1 },
  flyer_radius = { type = "number", default = 3, above = 0 },      -- m, flyer centreline
  flyer_thickness = { type = "number", default = 0.4, above = 0 }, -- m, flyer, radial
  flyer_voussoirs = { type = "number", default = 6, integer = true, min = 1 },
  flyer_drop = { type = "number", default = 0, min = 0 },          -- m, pier top to flyer crown joint's top
  buttress_width = { type = "number", default = 1.2, above = 0 },  -- m, along x (> flyer_thickness)
  buttress_blocks = { type = "number", default = 1, integer = true, min = 1 },
  depth = { type = "number", default = 1, above = 0 },             -- m, along y (all blocks)
  density = { type = "number", default = 2400, above = 0 },        -- kg/m^3
}

local function fail(message)
  error("models.buttressed_vault: " .. message, 3)
end

return function(opts)
  local o = options.check("models.buttressed_vault", opts, spec)
  semicircle.check_thickness("models.buttressed_vault", o)
  if o.pier_width <= o.thickness then
    fail(("pier_width must be > thickness (%g): the vault springs from the pier's top; got %g")
      :format(o.thickness, o.pier_width))
  end
  if o.flyer_thickness >= 2 * o.flyer_radius then
    fail(("flyer_thickness must be < 2 * flyer_radius (%g), got %g"):format(2 * o.flyer_radius, o.flyer_thickness))
  end
  if o.buttress_width <= o.flyer_thickness then
    fail(("buttress_width must be > flyer_thickness (%g): the flyer springs from the buttress's top; got %g")
      :format(o.flyer_thickness, o.buttress_width))
  end
  local h, d = o.pier_height, o.depth
  local flyer_centre = h - o.flyer_drop - o.flyer_thickness / 2 - o.flyer_radius
  if flyer_centre <= 0 then
    fail(("the flyer does not fit under the pier's top: flyer_radius + flyer_thickness / 2 + flyer_drop "
      .. "must be < pier_height (%g), got %g"):format(h, h - flyer_centre))
  end
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local y0, y1 = -d / 2, d / 2
  local s = ashlar.structure()

  for k = 1, o.voussoirs do
    s:add(semicircle.voussoir(k, o.voussoirs, inner, outer, y0, y1, o.density):translated{ 0, 0, h },
          { name = ("vault %d"):format(k) })
  end

  -- One side, mirrored by `side` (-1 left, +1 right); x measured outwards.
  local function add_side(side, label)
    local function at(x) return side * x end
    local function column(name, x_inner, width, height, blocks)
      local block_height = height / blocks
      for i = 1, blocks do
        s:add(ashlar.box{ size = { width, d, block_height }, center = { at(x_inner + width / 2), 0, (i - 0.5) * block_height },
                          density = o.density }, { name = ("%s %s %d"):format(label, name, i) })
      end
      s:add(ashlar.box{ size = { width, d, width / 2 }, center = { at(x_inner + width / 2), 0, -width / 4 },
                        density = o.density }, { support = true, name = ("%s %s ground"):format(label, name) })
    end
    column("pier", inner, o.pier_width, h, o.pier_blocks)

    local wall = inner + o.pier_width  -- the pier's outer face
    local fin, fout = o.flyer_radius - o.flyer_thickness / 2, o.flyer_radius + o.flyer_thickness / 2
    for k = 1, o.flyer_voussoirs do
      s:add(semicircle.flyer_voussoir(k, o.flyer_voussoirs, fin, fout, at(wall), flyer_centre, side, y0, y1, o.density),
            { name = ("%s flyer %d"):format(label, k) })
    end
    column("buttress", wall + fin, o.buttress_width, flyer_centre, o.buttress_blocks)
  end
  add_side(-1, "left")
  add_side(1, "right")
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
