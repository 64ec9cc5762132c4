-- Geometry shared by the semicircular generators (models.arch,
-- models.barrel_vault, and the flyers of models.flying_buttress and
-- models.buttressed_vault): radial joints in the x-z plane around the y axis,
-- springing at z = 0, and the two supports under the springings.
local ashlar = require "ashlar"

local semicircle = {}

-- Rejects a thickness that leaves no intrados; `generator` names the caller.
function semicircle.check_thickness(generator, o)
  if o.thickness >= 2 * o.radius then
    error(("%s: thickness must be < 2 * radius (%g), got %g"):format(generator, 2 * o.radius,
      o.thickness), 3)
  end
end

-- Direction (cos, sin) of radial joint k of n (k = 0 at the left springing).
-- The springings are set exactly so that they are horizontal: sin(math.pi)
-- is not 0 in floating point.
function semicircle.joint_direction(k, n)
  if k == 0 then return -1, 0 end
  if k == n then return 1, 0 end
  local angle = math.pi * (1 - k / n)
  return math.cos(angle), math.sin(angle)
end

-- The solid between radial joints k - 1 and k, from y0 to y1. Vertex i of
-- one joint rectangle faces vertex i of the next, as ashlar.loft requires.
function semicircle.voussoir(k, n, inner, outer, y0, y1, density)
  local function joint(c, s)
    return { { inner * c, y0, inner * s }, { outer * c, y0, outer * s },
             { outer * c, y1, outer * s }, { inner * c, y1, inner * s } }
  end
  return ashlar.loft(joint(semicircle.joint_direction(k - 1, n)),
                     joint(semicircle.joint_direction(k, n)), { density = density })
end

-- Direction (cos, sin) of joint k of n of a flyer, the outer half of a
-- semicircular arch: k = 0 is the crown joint (vertical), k = n the
-- springing (horizontal), both set exactly.
function semicircle.flyer_joint_direction(k, n)
  if k == 0 then return 0, 1 end
  if k == n then return 1, 0 end
  local angle = 0.5 * math.pi * (1 - k / n)
  return math.cos(angle), math.sin(angle)
end

-- Voussoir k of n of a flyer centred on (cx, cz), from y0 to y1, between
-- radii inner and outer, reaching towards +x (side = 1) or -x (side = -1).
function semicircle.flyer_voussoir(k, n, inner, outer, cx, cz, side, y0, y1, density)
  local function joint(j)
    local c, s = semicircle.flyer_joint_direction(j, n)
    local a, b = { cx + side * inner * c, cz + inner * s }, { cx + side * outer * c, cz + outer * s }
    return { { a[1], y0, a[2] }, { b[1], y0, b[2] }, { b[1], y1, b[2] }, { a[1], y1, a[2] } }
  end
  return ashlar.loft(joint(k - 1), joint(k), { density = density })
end

-- Adds "support left" and "support right": they reach from the intrados
-- outwards, so they never meet under the arch, and past the extrados so the
-- springing joints rest inside them.
function semicircle.add_supports(s, inner, thickness, length, density)
  local width = 2 * thickness
  for _, side in ipairs{ { -1, "support left" }, { 1, "support right" } } do
    s:add(ashlar.box{ size = { width, length, thickness },
                      center = { side[1] * (inner + width / 2), 0, -thickness / 2 },
                      density = density }, { support = true, name = side[2] })
  end
end

return semicircle
