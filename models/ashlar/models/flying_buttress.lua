-- models.flying_buttress: the thesis's figures 6 and 7 (Shin 2014) in the
-- x-z plane, depth along y centred on y = 0:
--
--   wall (support) | flyer (quarter arch) -> pier top | pinnacle
--                                          pier (N blocks)
--                                          ground (support)
--
-- The flyer is the right half of a semicircular arch of centreline radius
-- `radius`, centred on (0, pier_height): its crown joint is vertical and
-- abuts the wall (a support block whose face is the plane x = 0), and its
-- springing joint is horizontal and rests on the pier's top face at its
-- inner edge. It is held like half of a full arch (whose crown joint
-- carries the thrust), except that friction at the wall can also carry
-- shear; it pushes the pier outwards with its thrust, at the pier's top. The pinnacle is a box on the rest of the pier's top,
-- outboard of the flyer's springing: its weight moves the resultant in the
-- pier's bed joints inwards (figure 7, right), which is what lets a
-- slender pier stand. At the defaults (friction 0.7) the smallest pinnacle
-- that lets the buttress stand is 2.3635 m high at 256 voussoirs; the
-- flyer's hinges can form only at joints, so the answer is not monotone in
-- the count (16, 24, 32, 48 give 2.18, 2.30, 2.24, 2.347) and stays within
-- 1% from 60 voussoirs on (the default: 2.346, -0.74%;
-- scripts/model_discretisation.lua), whatever the number of pier blocks (1, 4 and 16
-- give the same: the pier overturns as a whole about its outer toe). The
-- default 4 m pinnacle stands; none, or a 2 m one, does not. (Measured
-- with analyze's tolerance = 1e-7: at the default 1e-10 the solver stops
-- "inaccurate" on this structure, whose wall joint works by friction.)
-- Joints are radial in the flyer and horizontal in the
-- pier; every face is planar.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local semicircle = require "ashlar.models.semicircle"

local spec = {
  radius = { type = "number", default = 6, above = 0 },          -- m, flyer centreline
  thickness = { type = "number", default = 0.8, above = 0 },     -- m, flyer, radial
  voussoirs = { type = "number", default = 60, integer = true, min = 1 },  -- flyer
  depth = { type = "number", default = 1, above = 0 },           -- m, along y (all blocks)
  pier_width = { type = "number", default = 1.4, above = 0 },    -- m, along x
  pier_height = { type = "number", default = 12, above = 0 },    -- m, ground to flyer springing
  pier_blocks = { type = "number", default = 4, integer = true, min = 1 },
  pinnacle_height = { type = "number", default = 4, min = 0 },   -- m; 0: no pinnacle
  density = { type = "number", default = 2400, above = 0 },      -- kg/m^3
}

local function fail(message)
  error("models.flying_buttress: " .. message, 3)
end

return function(opts)
  local o = options.check("models.flying_buttress", opts, spec)
  if o.thickness >= 2 * o.radius then
    fail(("thickness must be < 2 * radius (%g), got %g"):format(2 * o.radius, o.thickness))
  end
  if o.pier_width <= o.thickness then
    fail(("pier_width must be > thickness (%g): the flyer's springing rests on the pier's top, "
      .. "the pinnacle beside it; got %g"):format(o.thickness, o.pier_width))
  end
  local t, d, h, n = o.thickness, o.depth, o.pier_height, o.voussoirs
  local inner, outer = o.radius - t / 2, o.radius + t / 2
  local y0, y1 = -d / 2, d / 2
  local s = ashlar.structure()

  -- Flyer: voussoir 1 against the wall to voussoir N on the pier.
  for i = 1, n do
    s:add(semicircle.flyer_voussoir(i, n, inner, outer, 0, h, 1, y0, y1, o.density),
          { name = ("voussoir %d"):format(i) })
  end

  -- Pier: from the flyer's intrados springing outwards, pier_width wide.
  local x0 = inner
  local block_height = h / o.pier_blocks
  for i = 1, o.pier_blocks do
    s:add(ashlar.box{ size = { o.pier_width, d, block_height },
                      center = { x0 + o.pier_width / 2, 0, (i - 0.5) * block_height },
                      density = o.density }, { name = ("pier %d"):format(i) })
  end

  -- Pinnacle: the rest of the pier's top, outboard of the springing joint.
  if o.pinnacle_height > 0 then
    local width = o.pier_width - t
    s:add(ashlar.box{ size = { width, d, o.pinnacle_height },
                      center = { x0 + t + width / 2, 0, h + o.pinnacle_height / 2 },
                      density = o.density }, { name = "pinnacle" })
  end

  -- Supports: the piece of the wall the flyer props (x <= 0, three flyer
  -- thicknesses high around the crown joint) and the ground under the pier
  -- (its footprint, half the pier's width deep). They never touch: the wall
  -- is at x <= 0 and the pier starts at x = inner > 0.
  s:add(ashlar.box{ size = { t, d, 3 * t }, center = { -t / 2, 0, h + o.radius },
                    density = o.density }, { support = true, name = "wall" })
  s:add(ashlar.box{ size = { o.pier_width, d, o.pier_width / 2 },
                    center = { x0 + o.pier_width / 2, 0, -o.pier_width / 4 },
                    density = o.density }, { support = true, name = "ground" })
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
