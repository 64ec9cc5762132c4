-- models.barrel_vault: a semicircular barrel vault along y, on two long
-- support blocks. Its cross-section is models.arch's (x-z plane, centre on
-- the y axis, springing at z = 0, radial joints); the length is centred on
-- y = 0 and cut into courses by ring joints, stacked or in running bond.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local spec = {
  radius = { type = "number", default = 3, above = 0 },       -- m, of the centreline
  thickness = { type = "number", default = 0.3, above = 0 },  -- m, radial
  -- One voussoir would span the whole half circle with a flat chord: no solid.
  voussoirs = { type = "number", default = 15, integer = true, min = 2 },
  length = { type = "number", default = 3, above = 0 },       -- m, along y
  courses = { type = "number", default = 6, integer = true, min = 1 },
  bond = { type = "string", default = "stacked", one_of = { "stacked", "running" } },
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
  local o = options.check("models.barrel_vault", opts, spec)
  if o.thickness >= 2 * o.radius then
    error(("models.barrel_vault: thickness must be < 2 * radius (%g), got %g"):format(2 * o.radius,
      o.thickness), 2)
  end
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local n = o.voussoirs
  local course_length = o.length / o.courses
  -- Direction of radial joint k (k = 0 at the left springing); the springings
  -- are set exactly so that they are horizontal.
  local function direction(k)
    if k == 0 then return -1, 0 end
    if k == n then return 1, 0 end
    local angle = math.pi * (1 - k / n)
    return math.cos(angle), math.sin(angle)
  end
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
    local c0, s0 = direction(i - 1)
    local c1, s1 = direction(i)
    for j = 1, #cuts - 1 do
      s:add(ashlar.loft(joint(c0, s0, inner, outer, cuts[j], cuts[j + 1]),
                        joint(c1, s1, inner, outer, cuts[j], cuts[j + 1]), { density = o.density }),
            { name = ("voussoir %d course %d"):format(i, j) })
    end
  end
  -- As in models.arch: from the intrados outwards, past the extrados.
  local width = 2 * o.thickness
  for _, side in ipairs{ { -1, "support left" }, { 1, "support right" } } do
    s:add(ashlar.box{ size = { width, o.length, o.thickness },
                      center = { side[1] * (inner + width / 2), 0, -o.thickness / 2 },
                      density = o.density }, { support = true, name = side[2] })
  end
  return s
end
