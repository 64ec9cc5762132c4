-- models.barrel_vault: a semicircular barrel vault along y, on two long
-- support blocks. Its cross-section is models.arch's (x-z plane, centre on
-- the y axis, springing at z = 0, radial joints); the length is centred on
-- y = 0 and cut into courses by ring joints, stacked or in running bond.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local semicircle = require "ashlar.models.semicircle"

local spec = {
  radius = { type = "number", default = 3, above = 0 },       -- m, of the centreline
  -- t/R = 0.15: the minimum for a semicircular vault is about 0.1075.
  thickness = { type = "number", default = 0.45, above = 0 },  -- m, radial
  -- One voussoir would span the whole half circle with a flat chord: no solid.
  -- Within 1% of the minimum thickness from 24 voussoirs on
  -- (scripts/model_discretisation.lua).
  voussoirs = { type = "number", default = 24, integer = true, min = 2 },
  length = { type = "number", default = 3, above = 0 },       -- m, along y
  courses = { type = "number", default = 6, integer = true, min = 1 },
  bond = { type = "string", default = "stacked", one_of = { "stacked", "running" } },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
}

return function(opts)
  local o = options.check("models.barrel_vault", opts, spec)
  options.limit_blocks("models.barrel_vault", o.voussoirs * (o.courses + 1),
    ("voussoirs = %d with courses = %d"):format(o.voussoirs, o.courses))
  semicircle.check_thickness("models.barrel_vault", o)
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local n = o.voussoirs
  local course_length = o.length / o.courses
  local s = ashlar.structure()
  for i = 1, n do
    -- Running bond: every second row of voussoirs starts and ends with a
    -- half course so that the ring joints are staggered and the ends flush.
    local cuts = { -o.length / 2 }
    if o.bond == "running" and i % 2 == 0 then
      for c = 1, o.courses do cuts[#cuts + 1] = -o.length / 2 + (c - 0.5) * course_length end
    else
      for c = 1, o.courses - 1 do cuts[#cuts + 1] = -o.length / 2 + c * course_length end
    end
    cuts[#cuts + 1] = o.length / 2
    for j = 1, #cuts - 1 do
      s:add(semicircle.voussoir(i, n, inner, outer, cuts[j], cuts[j + 1], o.density),
            { name = ("voussoir %d course %d"):format(i, j) })
    end
  end
  semicircle.add_supports(s, inner, o.thickness, o.length, o.density)
  return s
end
