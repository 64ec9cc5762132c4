-- models.cable_stayed_bridge: the thesis's figure 3 (Shin 2014): a vertical
-- masonry arch holding up, by cables, a walkway that is an arch in plan.
--
--   * vertical arch: a semicircle of centreline radius `arch_radius` in the
--     x-z plane (depth `arch_depth` along y, centred on y = 0), springing at
--     z = 0, radial joints, on two support boxes under its springings
--     (from the intrados outwards, twice the thickness wide, as deep as the
--     arch, their tops at z = 0);
--   * walkway: a circular arch in the horizontal plane, its centreline
--     running from (-span/2, 0) to (span/2, 0) through (0, -deck_rise),
--     `deck_blocks` blocks cut by vertical joints radial in plan, `deck_width`
--     wide (radially), from z = deck_height up to deck_height + deck_depth, so
--     every block's top face is horizontal. Its end joints abut two supports:
--     prisms that continue the walkway along its end tangents, `deck_width`
--     long, from the ground (z = 0) to the walkway's top;
--   * cables: every walkway block but the two end ones (which rest on the
--     supports) hangs from one cable, attached at its joint farther from
--     the crown, so the crown joint has none (hence an even deck_blocks):
--     from the block's top vertex on the inner (+y, arch) side of that joint
--     to the arch's intrados vertex on the walkway's side (y = -arch_depth/2)
--     at the joint nearest in x (not a springing), on the voussoir nearer the
--     crown (at the crown joint, the one on the cable's side).
-- The cables' ends are block vertices, so an optimisation that moves the
-- vertices (welding coincident points) moves the cables with them. Every
-- contact between free blocks is a whole shared face, and the two halves
-- are mirror images about x = 0 to the bit.
--
-- Blocks, in order: "arch voussoir 1".."arch voussoir N" (left to right),
-- "deck 1".."deck M" (left to right), "arch support left", "arch support
-- right", "deck support left", "deck support right". Cables from left to
-- right.
--
-- The defaults give the thesis's figure 3a: the walkway is too heavy for
-- the arch. The arch alone stands (t/R = 0.133 > 0.1075), and the walkway
-- would hang from a rigid arch (its 0.6 x 0.6 m section carries in its
-- joints, by friction, the torsion of a cable at one edge; a 1 x 0.3 m one
-- does not), but the cables' pull, down and towards the walkway, is more
-- than the arch can take: infeasibility 0.30 at friction 0.7, mostly the
-- arch toppling towards the walkway (0.001 with arch_depth = 1). It stands
-- with deck_density up to 768 (a third of the default).
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local GENERATOR = "models.cable_stayed_bridge"

local spec = {
  arch_radius = { type = "number", default = 6, above = 0 },           -- m, centreline
  arch_thickness = { type = "number", default = 0.8, above = 0 },      -- m, radial
  arch_depth = { type = "number", default = 0.6, above = 0 },          -- m, along y
  arch_voussoirs = { type = "number", default = 10, integer = true, min = 2 },
  density = { type = "number", default = 2400, above = 0 },            -- kg/m^3, arch
  span = { type = "number", default = 9, above = 0 },                  -- m, walkway centreline chord
  deck_rise = { type = "number", default = 3, above = 0 },             -- m, along -y at mid-span
  deck_height = { type = "number", default = 1, min = 0 },             -- m, underside
  deck_width = { type = "number", default = 0.6, above = 0 },          -- m, horizontal, radial
  deck_depth = { type = "number", default = 0.6, above = 0 },          -- m, vertical
  deck_blocks = { type = "number", default = 10, integer = true, min = 4 },
  deck_density = { type = "number", default = 2400, above = 0 },       -- kg/m^3
  cable_mass = { type = "number", default = 0, min = 0 },              -- kg/m
}

-- Blames the generator's caller (fail -> generator -> caller).
local function fail(message)
  error(GENERATOR .. ": " .. message, 3)
end

return function(opts)
  local o = options.check(GENERATOR, opts, spec)
  local n, m = o.arch_voussoirs, o.deck_blocks
  if o.arch_thickness >= 2 * o.arch_radius then
    fail(("arch_thickness must be < 2 * arch_radius (%g), got %g"):format(2 * o.arch_radius, o.arch_thickness))
  end
  -- The crown joint carries no cable: an even count keeps both halves alike.
  if m % 2 ~= 0 then
    fail(("deck_blocks: expected an even count (both halves alike), got %d"):format(m))
  end
  if o.deck_rise >= o.span / 2 then
    fail(("deck_rise must be < span / 2 (%g): the walkway is a segment of a circle in plan, got %g")
      :format(o.span / 2, o.deck_rise))
  end

  -- Walkway centreline in plan: a circle of radius rp centred on (0, yc),
  -- the point at angle phi (0 at mid-span) is (rp sin phi, yc - rp cos phi).
  local c, f = o.span / 2, o.deck_rise
  local rp = (c * c + f * f) / (2 * f)
  local yc = rp - f
  if o.deck_width >= 2 * rp then
    fail(("deck_width must be < 2 * the walkway's radius in plan (%g), got %g"):format(2 * rp, o.deck_width))
  end
  local half_angle = math.asin(c / rp)
  -- Inner (+y side, towards the centre) and outer points of walkway joint k;
  -- mirrored so the walkway is exactly symmetric about x = 0.
  local deck_joints = {}
  local r_in, r_out = rp - o.deck_width / 2, rp + o.deck_width / 2
  for k = 0, m // 2 do
    local phi = -half_angle + 2 * half_angle * k / m
    local sin, cos = math.sin(phi), math.cos(phi)
    deck_joints[k] = { inner = { r_in * sin, yc - r_in * cos }, outer = { r_out * sin, yc - r_out * cos } }
  end
  deck_joints[m // 2].inner[1], deck_joints[m // 2].outer[1] = 0, 0
  for k = m // 2 + 1, m do
    local j = deck_joints[m - k]
    deck_joints[k] = { inner = { -j.inner[1], j.inner[2] }, outer = { -j.outer[1], j.outer[2] } }
  end

  -- Vertical arch joints in x-z: intrados and extrados points, mirrored too;
  -- the springing joints lie exactly on z = 0, the supports' tops.
  local ri, ro = o.arch_radius - o.arch_thickness / 2, o.arch_radius + o.arch_thickness / 2
  local arch_joints = {}
  for k = 0, n // 2 do
    local angle = math.pi * (1 - k / n)
    local cos, sin = math.cos(angle), math.sin(angle)
    arch_joints[k] = { ix = ri * cos, iz = ri * sin, ex = ro * cos, ez = ro * sin }
  end
  arch_joints[0].iz, arch_joints[0].ez = 0, 0
  if n % 2 == 0 then arch_joints[n // 2].ix, arch_joints[n // 2].ex = 0, 0 end
  for k = n // 2 + 1, n do
    local j = arch_joints[n - k]
    arch_joints[k] = { ix = -j.ix, iz = j.iz, ex = -j.ex, ez = j.ez }
  end

  -- The walkway's supports continue it along its end tangents.
  local tangent = { math.cos(half_angle), math.sin(half_angle) } -- at the right end, outwards
  local top = o.deck_height + o.deck_depth
  local reach = 0 -- largest |x| of the walkway and its supports
  for _, p in ipairs{ deck_joints[m].inner, deck_joints[m].outer } do
    reach = math.max(reach, math.abs(p[1]) + o.deck_width * tangent[1])
  end
  -- The walkway passes under the arch: clear of its intrados there.
  if reach >= ri or top >= math.sqrt(ri * ri - reach * reach) then
    fail(("the walkway and its supports (out to |x| = %g, up to z = %g) must pass under the arch's intrados "
      .. "(radius %g); make span, deck_width, deck_height or deck_depth smaller or arch_radius larger")
      :format(reach, top, ri))
  end

  local s = ashlar.structure()
  local y0, y1 = -o.arch_depth / 2, o.arch_depth / 2
  local function arch_section(j)
    return { { j.ix, y0, j.iz }, { j.ex, y0, j.ez }, { j.ex, y1, j.ez }, { j.ix, y1, j.iz } }
  end
  for k = 1, n do
    s:add(ashlar.loft(arch_section(arch_joints[k - 1]), arch_section(arch_joints[k]), { density = o.density }),
          { name = ("arch voussoir %d"):format(k) })
  end
  local z0 = o.deck_height
  local function deck_section(j)
    return { { j.inner[1], j.inner[2], z0 }, { j.outer[1], j.outer[2], z0 },
             { j.outer[1], j.outer[2], top }, { j.inner[1], j.inner[2], top } }
  end
  local deck = {}
  for k = 1, m do
    deck[k] = s:add(ashlar.loft(deck_section(deck_joints[k - 1]), deck_section(deck_joints[k]),
                                { density = o.deck_density }),
                    { name = ("deck %d"):format(k) })
  end

  local width = 2 * o.arch_thickness
  for _, side in ipairs{ { -1, "arch support left" }, { 1, "arch support right" } } do
    s:add(ashlar.box{ size = { width, o.arch_depth, o.arch_thickness },
                      center = { side[1] * (ri + width / 2), 0, -o.arch_thickness / 2 },
                      density = o.density }, { support = true, name = side[2] })
  end
  for _, side in ipairs{ { -1, 0, "deck support left" }, { 1, m, "deck support right" } } do
    local j, sx = deck_joints[side[2]], side[1]
    local dx, dy = sx * o.deck_width * tangent[1], o.deck_width * tangent[2]
    s:add(ashlar.prism({ { j.inner[1], j.inner[2], 0 }, { j.outer[1], j.outer[2], 0 },
                         { j.outer[1] + dx, j.outer[2] + dy, 0 }, { j.inner[1] + dx, j.inner[2] + dy, 0 } },
                       { 0, 0, top }, { density = o.deck_density }),
          { support = true, name = side[3] })
  end

  -- Cables: from the block's vertex at the inner top corner of its joint
  -- farther from the crown to the nearest arch intrados vertex on the
  -- walkway's side; at the arch's crown joint, to the voussoir on the cable's
  -- side, so the bridge stays mirror-symmetric.
  for k = 2, m - 1 do
    local joint = k <= m // 2 and k - 1 or k
    local from = { deck_joints[joint].inner[1], deck_joints[joint].inner[2], top }
    -- A tie goes to the joint nearer the crown, on either side alike.
    local nearest = 1
    for a = 2, n - 1 do
      local d, best = math.abs(arch_joints[a].ix - from[1]), math.abs(arch_joints[nearest].ix - from[1])
      if d < best or (d == best and math.abs(arch_joints[a].ix) < math.abs(arch_joints[nearest].ix)) then
        nearest = a
      end
    end
    local x = arch_joints[nearest].ix
    local voussoir = (x < 0 or (x == 0 and from[1] > 0)) and nearest + 1 or nearest
    s:add_cable{ from = { block = deck[k], point = from },
                 to = { block = voussoir, point = { x, y0, arch_joints[nearest].iz } },
                 mass_per_length = o.cable_mass }
  end
  return s
end
