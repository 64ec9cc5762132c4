-- models.arch: a semicircular arch of voussoirs with radial joints, in the
-- x-z plane (depth along y, centred on y = 0), centre at the origin,
-- springing at z = 0, on two support blocks.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local semicircle = require "ashlar.models.semicircle"

local spec = {
  radius = { type = "number", default = 5, above = 0 },       -- m, of the centreline
  thickness = { type = "number", default = 0.6, above = 0 },  -- m, radial
  -- One voussoir would span the whole half circle with a flat chord: no solid.
  voussoirs = { type = "number", default = 31, integer = true, min = 2 },
  depth = { type = "number", default = 1, above = 0 },        -- m, along y
  shape = { type = "string", default = "semicircular", one_of = { "semicircular" } },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
}

return function(opts)
  local o = options.check("models.arch", opts, spec)
  semicircle.check_thickness("models.arch", o)
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local n = o.voussoirs
  local s = ashlar.structure()
  -- Voussoirs first, so that voussoir i is block i.
  for i = 1, n do
    s:add(semicircle.voussoir(i, n, inner, outer, -o.depth / 2, o.depth / 2, o.density),
          { name = ("voussoir %d"):format(i) })
  end
  semicircle.add_supports(s, inner, o.thickness, o.depth, o.density)
  return s
end
