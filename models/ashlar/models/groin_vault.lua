-- models.groin_vault: a cross (groin) vault over a square bay centred on
-- the z axis: two semicircular barrel vaults of the same radius, one along
-- x and one along y, springing at z = 0, intersecting along the diagonals
-- x = ±y (the groins), on four corner supports.
--
-- The vault is four webs. The web over the bay's face y = +side/2 is the
-- part of the barrel along y with y >= |x| (where its intrados is the
-- higher of the two); the others are that web turned by the square's
-- quarter turns. Each web has the arch section of models.arch (radial
-- joints, straight chords for intrados and extrados) and an even number of
-- voussoirs, so that the crown joint is the vertical plane through the
-- axis and every voussoir lies on one side of it: each voussoir is then
-- one block, its section extruded from the groin plane (y = |x|, on which
-- it ends with a planar face) to the bay's face. The two webs meeting on a
-- groin have the same section mirrored, so their faces on the diagonal
-- plane coincide voussoir by voussoir. Courses along the webs are not cut
-- (one block per voussoir and web).
--
-- Minimum thickness (friction 0.7, default side, bisection with analyze's
-- tolerance = 1e-7): t/R = 0.1411 with 16, 24, 32 and 64 voussoirs (0.1412
-- with 128). Hinges form only at joints, so coarser or odd multiples miss
-- it: 4, 6, 8, 10, 12, 14, 20 give 0.1151, 0.1372, 0.1415, 0.1388, 0.1365,
-- 0.1404, 0.1396. The default 16 is within 0.05 %. The defaults (t/R = 0.1)
-- do not stand; t/R = 0.2 does.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local semicircle = require "ashlar.models.semicircle"

local spec = {
  radius = { type = "number", default = 3, above = 0 },       -- m, of the centreline
  thickness = { type = "number", default = 0.3, above = 0 },  -- m, radial
  voussoirs = { type = "number", default = 16, integer = true, min = 2 },  -- per web, even
  side = { type = "number", above = 0 },                      -- m, of the square bay; 2 * (radius + thickness)
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
}

local function fail(message)
  error("models.groin_vault: " .. message, 3)
end

-- The four webs: (u, v) in the web's frame (u across, v along, towards the
-- bay's face) to (x, y). Exact sign swaps, so the webs are exact images.
local webs = {
  { name = "north", map = function(u, v) return u, v end },     -- face y = +side/2
  { name = "west", map = function(u, v) return -v, u end },     -- face x = -side/2
  { name = "south", map = function(u, v) return -u, -v end },   -- face y = -side/2
  { name = "east", map = function(u, v) return v, -u end },     -- face x = +side/2
}

return function(opts)
  local o = options.check("models.groin_vault", opts, spec)
  semicircle.check_thickness("models.groin_vault", o)
  if o.voussoirs % 2 ~= 0 then
    fail(("voussoirs: a groin vault needs an even count (a crown joint on the axis), got %d"):format(o.voussoirs))
  end
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  o.side = o.side or 2 * (o.radius + o.thickness)
  local half = o.side / 2
  if half <= outer then
    -- The springing voussoir's extrados corner would reach the bay's face.
    fail(("side must be > 2 * (radius + thickness / 2) (%g), got %g"):format(2 * outer, o.side))
  end
  local n = o.voussoirs
  local s = ashlar.structure()
  for _, web in ipairs(webs) do
    for i = 1, n do
      -- Section corners (u, z) of voussoir i, from the springing on the
      -- left as seen from the bay's centre facing the web.
      local section = {}
      for _, k in ipairs{ i - 1, i } do
        local c, si = semicircle.joint_direction(k, n)
        if 2 * k == n then c, si = 0, 1 end   -- the crown joint, exactly vertical
        section[#section + 1] = { inner * c, inner * si }
        section[#section + 1] = { outer * c, outer * si }
      end
      section = { section[1], section[2], section[4], section[3] }
      -- Every corner has |u| on the groin: the section is on one side of
      -- u = 0, so the groin face lies in one diagonal plane.
      local groin, face = {}, {}
      for j, p in ipairs(section) do
        local x, y = web.map(p[1], math.abs(p[1]))
        groin[j] = { x, y, p[2] }
        x, y = web.map(p[1], half)
        face[j] = { x, y, p[2] }
      end
      s:add(ashlar.loft(groin, face, { density = o.density }),
            { name = ("%s voussoir %d"):format(web.name, i) })
    end
  end
  -- Corner supports: from the intrados springing (|x|, |y| >= inner) to the
  -- bay's corner, as thick as the vault, tops at z = 0. The springing faces
  -- of the two webs meeting at a corner rest on it.
  local width = half - inner
  local corners = { { -1, 1, "northwest" }, { -1, -1, "southwest" }, { 1, -1, "southeast" }, { 1, 1, "northeast" } }
  for _, c in ipairs(corners) do
    s:add(ashlar.box{ size = { width, width, o.thickness },
                      center = { c[1] * (inner + width / 2), c[2] * (inner + width / 2), -o.thickness / 2 },
                      density = o.density }, { support = true, name = "support " .. c[3] })
  end
  return s
end
