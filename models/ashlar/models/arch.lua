-- models.arch: a semicircular arch of voussoirs with radial joints, in the
-- x-z plane (depth along y, centred on y = 0), centre at the origin,
-- springing at z = 0, on two support blocks.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local spec = {
  radius = { type = "number", default = 5, above = 0 },       -- m, of the centreline
  thickness = { type = "number", default = 0.6, above = 0 },  -- m, radial
  -- One voussoir would span the whole half circle with a flat chord: no solid.
  voussoirs = { type = "number", default = 31, integer = true, min = 2 },
  depth = { type = "number", default = 1, above = 0 },        -- m, along y
  shape = { type = "string", default = "semicircular", one_of = { "semicircular" } },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
}

-- The joint rectangle along the direction (c, s) in the x-z plane, from y0
-- to y1. Vertex k of one joint faces vertex k of the next, as ashlar.loft
-- requires.
local function joint(c, s, inner, outer, y0, y1)
  return { { inner * c, y0, inner * s }, { outer * c, y0, outer * s },
           { outer * c, y1, outer * s }, { inner * c, y1, inner * s } }
end

return function(opts)
  local o = options.check("models.arch", opts, spec)
  if o.thickness >= 2 * o.radius then
    error(("models.arch: thickness must be < 2 * radius (%g), got %g"):format(2 * o.radius, o.thickness), 2)
  end
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local n = o.voussoirs
  -- Direction of radial joint k (k = 0 at the left springing); the springings
  -- are set exactly so that they are horizontal (sin(math.pi) is not 0 in
  -- floating point).
  local function direction(k)
    if k == 0 then return -1, 0 end
    if k == n then return 1, 0 end
    local angle = math.pi * (1 - k / n)
    return math.cos(angle), math.sin(angle)
  end
  local s = ashlar.structure()
  -- Voussoirs first, so that voussoir i is block i.
  for i = 1, n do
    local c0, s0 = direction(i - 1)
    local c1, s1 = direction(i)
    s:add(ashlar.loft(joint(c0, s0, inner, outer, -o.depth / 2, o.depth / 2),
                      joint(c1, s1, inner, outer, -o.depth / 2, o.depth / 2), { density = o.density }),
          { name = ("voussoir %d"):format(i) })
  end
  -- The supports reach from the intrados outwards, so they never meet under
  -- the arch, and past the extrados so the springing joints rest inside them.
  local width = 2 * o.thickness
  for _, side in ipairs{ { -1, "support left" }, { 1, "support right" } } do
    s:add(ashlar.box{ size = { width, o.depth, o.thickness },
                      center = { side[1] * (inner + width / 2), 0, -o.thickness / 2 },
                      density = o.density }, { support = true, name = side[2] })
  end
  return s
end
