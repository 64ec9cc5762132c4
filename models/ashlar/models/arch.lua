-- models.arch: an arch of voussoirs in the x-z plane (depth along y,
-- centred on y = 0), symmetric about x = 0, springing at z = 0, on two
-- support blocks. Shapes: semicircular, pointed, segmental, elliptical,
-- catenary; joints normal to the centreline ("radial") or vertical. The
-- joint geometry is in ashlar.models.arch_shapes.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local arch_shapes = require "ashlar.models.arch_shapes"

local spec = {
  shape = { type = "string", default = "semicircular",
            one_of = { "semicircular", "pointed", "segmental", "elliptical", "catenary" } },
  -- radius (of the centreline; circular shapes) or span: defaults by shape below.
  radius = { type = "number", above = 0 },
  span = { type = "number", above = 0 },                      -- m, between centreline springings
  rise = { type = "number", above = 0 },                      -- m, of the centreline
  eccentricity = { type = "number", min = 0 },                -- pointed only, < 1
  thickness = { type = "number", default = 0.6, above = 0 },  -- m, normal to the centreline
  -- One voussoir would span the whole half circle with a flat chord: no solid.
  voussoirs = { type = "number", integer = true, min = 2 },   -- by shape: DEFAULT_VOUSSOIRS
  depth = { type = "number", default = 1, above = 0 },        -- m, along y
  joints = { type = "string", default = "radial", one_of = { "radial", "vertical" } },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
  abutments = { type = "table" },                             -- see abutment_spec
}

-- Piers under the springings, from z = 0 down to z = -height, reaching from
-- the intrados end of the springing joint outwards (width defaults to
-- twice the joint's length, as the supports without abutments).
local abutment_spec = {
  width = { type = "number", above = 0 },
  height = { type = "number", default = 2, above = 0 },
}

-- Level 4 blames the generator's caller from resolve (fail -> resolve ->
-- generator -> caller); the joint geometry reports from two calls deeper.
local function fail(message, level)
  error("models.arch: " .. message, level or 4)
end
local function fail_in_shapes(message) fail(message, 6) end

local circular = { semicircular = true, pointed = true, segmental = true }

-- The smallest counts from which the minimum thickness (no sliding) stays
-- within 1% of its value at 512 voussoirs (256 pointed) for every finer
-- count up to 64, at the default proportions (scripts/model_discretisation.lua).
-- A catenary's minimum thickness only measures its chords and tends to 0:
-- it takes the semicircle's count.
local DEFAULT_VOUSSOIRS = { semicircular = 24, pointed = 26, segmental = 22, elliptical = 30, catenary = 24 }

-- Fills in the shape's dimensions and checks what the shape allows.
local function resolve(o)
  local shape = o.shape
  local function reject(key, why)
    if o[key] ~= nil then fail(("%s: not an option of a %s arch (%s)"):format(key, shape, why)) end
  end
  if shape ~= "pointed" then reject("eccentricity", "only of a pointed one") end
  if not circular[shape] and o.joints == "vertical" then
    fail(("joints = \"vertical\" is available for the circular shapes (semicircular, pointed, segmental), "
      .. "not for a %s arch"):format(shape))
  end
  if shape == "semicircular" or shape == "pointed" then
    reject("rise", "it follows from the radius")
    if shape == "pointed" then
      o.eccentricity = o.eccentricity or 0.2
      if o.eccentricity >= 1 then fail(("eccentricity: must be < 1, got %g"):format(o.eccentricity)) end
    end
    local e = o.eccentricity or 0
    if o.radius and o.span then fail("give radius or span, not both") end
    o.radius = o.radius or (o.span and o.span / (2 * (1 - e))) or 5
    o.span = 2 * o.radius * (1 - e)
    o.voussoirs = o.voussoirs or DEFAULT_VOUSSOIRS[shape]
    if shape == "pointed" and o.voussoirs % 2 ~= 0 then
      fail(("voussoirs: a pointed arch needs an even count (both halves alike), got %d"):format(o.voussoirs))
    end
    if shape == "semicircular" and o.thickness >= 2 * o.radius then
      fail(("thickness must be < 2 * radius (%g), got %g"):format(2 * o.radius, o.thickness))
    end
    if shape == "pointed" and o.thickness >= o.span then
      fail(("thickness must be < span = 2 * radius * (1 - eccentricity) (%g), got %g"):format(o.span, o.thickness))
    end
    return
  end
  reject("radius", "give span and rise")
  o.span = o.span or 10
  o.rise = o.rise or ({ segmental = 0.25, elliptical = 1 / 3, catenary = 0.5 })[shape] * o.span
  o.voussoirs = o.voussoirs or DEFAULT_VOUSSOIRS[shape]
  if o.thickness >= 2 * o.rise then
    fail(("thickness must be < 2 * rise (%g), got %g"):format(2 * o.rise, o.thickness))
  end
  if shape == "segmental" and o.rise >= o.span / 2 then
    fail(("rise: a segmental arch needs rise < span / 2 (%g), got %g"):format(o.span / 2, o.rise))
  end
  if shape == "elliptical" then
    -- The offsets of the centreline stay regular while half the thickness is
    -- below the smallest radius of curvature, min(a^2 / b, b^2 / a).
    local a, b = o.span / 2, o.rise
    local limit = 2 * math.min(a * a / b, b * b / a)
    if o.thickness >= limit then
      fail(("thickness must be < 2 * the smallest radius of curvature of the ellipse (%g), got %g")
        :format(limit, o.thickness))
    end
  end
  if shape == "catenary" then
    local a = arch_shapes.catenary_parameter(o.span, o.rise)
    if o.thickness >= 2 * a then
      fail(("thickness must be < 2 * the catenary's radius of curvature at the crown (%g), got %g")
        :format(2 * a, o.thickness))
    end
  end
end

return function(opts)
  local o = options.check("models.arch", opts, spec)
  local abutments = o.abutments and options.check("models.arch: abutments", o.abutments, abutment_spec)
  resolve(o)
  local joints = arch_shapes.joints(o, fail_in_shapes)
  local n, y0, y1 = o.voussoirs, -o.depth / 2, o.depth / 2
  local s = ashlar.structure()
  -- Voussoirs first, so that voussoir i is block i.
  for i = 1, n do
    s:add(arch_shapes.voussoir(joints[i - 1], joints[i], 0, 0, y0, y1, o.density),
          { name = ("voussoir %d"):format(i) })
  end
  -- The supports reach from the intrados end of the springing joint outwards,
  -- twice the joint's length, so they never meet under the arch and the
  -- joint rests inside their top faces (z = 0); their height is the thickness.
  -- With abutments, the abutments take that place and the supports sit
  -- under them, as wide, their tops at z = -height.
  local inner, length = -joints[0].ix, joints[0].ix - joints[0].ex
  local width, top = 2 * length, 0
  if abutments then
    width = abutments.width or width
    if width < length then
      error(("models.arch: abutments: width must be >= the springing joint's length (%g), got %g")
        :format(length, width), 2)
    end
    for _, side in ipairs{ { -1, "abutment left" }, { 1, "abutment right" } } do
      s:add(ashlar.box{ size = { width, o.depth, abutments.height },
                        center = { side[1] * (inner + width / 2), 0, -abutments.height / 2 },
                        density = o.density }, { name = side[2] })
    end
    top = -abutments.height
  end
  for _, side in ipairs{ { -1, "support left" }, { 1, "support right" } } do
    s:add(ashlar.box{ size = { width, o.depth, o.thickness },
                      center = { side[1] * (inner + width / 2), 0, top - o.thickness / 2 },
                      density = o.density }, { support = true, name = side[2] })
  end
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
