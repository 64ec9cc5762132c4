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
-- axis and every voussoir row lies on one side of it: its section then
-- ends on the groin plane (y = |x|) with a planar face. The two webs
-- meeting on a groin have the same section mirrored, so their faces on the
-- diagonal plane coincide row by row.
--
-- Each row is cut into courses by vertical joints perpendicular to the
-- web's axis (v = const), counted from the bay's face: the course length is
-- (side / 2 - outer * sin(pi / voussoirs)) / courses, so that the crown
-- rows hold `courses` whole courses. With bond = "running", every second
-- row (counted from the springings, so that rows i and N + 1 - i are
-- mirror images and the crown joint stays a plane of symmetry) starts at
-- the face with a half course. Near the groin the rows are shorter: a cut
-- is made only if it leaves the groin piece at least half a course long
-- where it is shortest, and the groin piece (from the groin face to its
-- first cut, of varying length with height) takes the rest of the row.
-- Every piece is a loft between two joint quads (groin face or vertical
-- cut, vertical cut or bay face); bed joints between rows are the radial
-- planes, shared by pieces whose extents along the axis overlap.
--
-- Minimum thickness (friction 0.7, default side, bisection with analyze's
-- tolerance = 1e-7): t/R = 0.1411 with 16, 24, 32 and 64 voussoirs (0.1412
-- with 128) and one course. Hinges form only at joints, so coarser or odd
-- multiples miss it: 4, 6, 8, 10, 12, 14, 20 give 0.1151, 0.1372, 0.1415,
-- 0.1388, 0.1365, 0.1404, 0.1396; the answer stays within 1% of its value
-- at 128 from 22 voussoirs on, the default (scripts/model_discretisation.lua,
-- which lets the default side follow the thickness as here). With 16
-- voussoirs, 1, 2 and 4 stacked courses and 4 and 8 courses in running
-- bond all give 0.1411 (bisection to 1e-5: 0.14115); 8 stacked courses
-- give 0.1465. The default t/R = 0.2 stands, stacked and in running bond;
-- t/R = 0.1 does not.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local semicircle = require "ashlar.models.semicircle"

local spec = {
  radius = { type = "number", default = 3, above = 0 },       -- m, of the centreline
  thickness = { type = "number", default = 0.6, above = 0 },  -- m, radial
  voussoirs = { type = "number", default = 22, integer = true, min = 2 },  -- per web, even
  side = { type = "number", above = 0 },                      -- m, of the square bay; 2 * (radius + thickness)
  courses = { type = "number", default = 4, integer = true, min = 1 },  -- along each web, at the crown
  bond = { type = "string", default = "stacked", one_of = { "stacked", "running" } },
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
  options.limit_blocks("models.groin_vault", 4 * o.voussoirs * (o.courses + 1),
    ("voussoirs = %d with courses = %d"):format(o.voussoirs, o.courses))
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
  -- The course length: `courses` whole courses between the bay's face and
  -- the crown rows' furthest groin corner (u = outer * sin(pi / n)).
  local crown_reach = outer * semicircle.joint_direction(n / 2 + 1, n)
  local course = (half - crown_reach) / o.courses
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
      local reach = 0   -- the row's furthest groin point from the axis
      for _, p in ipairs(section) do reach = math.max(reach, math.abs(p[1])) end
      -- Course joints v = const, counted from the bay's face: whole courses,
      -- or (running bond) a half course at the face then whole ones. Rows
      -- i and n + 1 - i are mirror images (the crown joint is a plane of
      -- symmetry), so rows alternate by their distance from the springing.
      -- A cut is made only if it leaves the groin piece at least half a
      -- course long where it is shortest (at the row's furthest groin
      -- corner); the groin piece takes the rest of the row, so no piece is
      -- shorter than half a course (bar a row with no cut at all).
      local offset = (o.bond == "running" and math.min(i, n + 1 - i) % 2 == 0) and 0.5 or 0
      local cuts = {}
      for k = 1, o.courses do
        local v = half - (k - offset) * course
        if v - reach < course / 2 * (1 - 1e-9) then break end
        table.insert(cuts, 1, v)
      end
      cuts[#cuts + 1] = half
      local function joint(v)   -- the section's quad on the plane v = const
        local quad = {}
        for j, p in ipairs(section) do
          local x, y = web.map(p[1], v)
          quad[j] = { x, y, p[2] }
        end
        return quad
      end
      local groin = {}
      for j, p in ipairs(section) do
        local x, y = web.map(p[1], math.abs(p[1]))
        groin[j] = { x, y, p[2] }
      end
      local from = groin
      for c, v in ipairs(cuts) do
        local to = joint(v)
        s:add(ashlar.loft(from, to, { density = o.density }),
              { name = ("%s voussoir %d course %d"):format(web.name, i, c) })
        from = to
      end
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
