-- models.arch_bridge: a multi-span masonry arch bridge in the x-z plane
-- (width `depth` along y, centred on y = 0), symmetric about x = 0, the
-- arches springing at z = 0.
--
-- Construction (every block a prism along y over an x-z section, so every
-- contact is a whole face or the overlap of two faces in one plane):
--   * arches: the voussoirs of models.arch (ashlar.models.arch_shapes, radial
--     joints) across the full width; arch p is centred on
--     x_p = (p - (spans + 1) / 2) * pitch, pitch = clear span + pier_width,
--     the clear span being the distance between the intrados springings;
--   * piers: between neighbouring arches, pier_width wide (from one arch's
--     intrados springing to the next one's), cut into `pier_courses` equal
--     courses from z = 0 down to z = -pier_height;
--   * abutments: at both ends, `abutment_width` from the intrados springing
--     outwards, from z = -pier_height up to the springing (z = 0) and, with
--     spandrels, on up to the deck level H outside the extrados springing
--     (an L-shaped section, so the abutment also backs the end spandrel);
--   * spandrels: over voussoir k a block whose section runs from the
--     voussoir's extrados chord straight up to H (vertical sides through the
--     chord's ends), so it rests on exactly that voussoir's extrados face and
--     touches its neighbours along whole vertical faces. Over each pier, the
--     gap between the two extrados springings is filled by a box from z = 0
--     to H ("pier P fill"). H is the highest extrados point plus `cover`;
--   * deck: one slab block over each block of the level z = H (left
--     abutment, the spandrels and pier fills from left to right, right
--     abutment), as long as the block under it, so each rests on one block;
--   * ground: one support slab under the piers and abutments.
-- Blocks, in order: "span P voussoir K", "spandrel P K", "pier P course C"
-- (C from the bottom), "pier P fill", "abutment left", "abutment right",
-- "deck I" (left to right), "ground" (the only support). The bare ring's
-- minimum thickness stays within 1% from 26 voussoirs on, the default
-- (scripts/model_discretisation.lua).
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local arch_shapes = require "ashlar.models.arch_shapes"

local GENERATOR = "models.arch_bridge"

local spec = {
  spans = { type = "number", default = 3, integer = true, min = 1 },
  shape = { type = "string", default = "segmental",
            one_of = { "segmental", "semicircular", "elliptical", "catenary" } },
  span = { type = "number", default = 8, above = 0 },          -- m, of the arch centreline
  rise = { type = "number", above = 0 },                       -- m, of the centreline; by shape
  thickness = { type = "number", default = 0.6, above = 0 },   -- m, of the arch ring
  depth = { type = "number", default = 4, above = 0 },         -- m, the bridge's width (y)
  voussoirs = { type = "number", default = 26, integer = true, min = 2 },
  pier_width = { type = "number", default = 1.5, above = 0 },  -- m, clear between springings
  pier_height = { type = "number", default = 4, above = 0 },   -- m, z = 0 down to the ground
  pier_courses = { type = "number", default = 4, integer = true, min = 1 },
  abutment_width = { type = "number", default = 3, above = 0 }, -- m, from the intrados springing out
  spandrel = { type = "boolean", default = true },
  cover = { type = "number", above = 0 },                      -- m, fill over the crown; thickness / 2
  deck = { type = "boolean" },  -- or { thickness = 0.3 }; taken out before the check, listed for it
  density = { type = "number", default = 2400, above = 0 },
}

local deck_spec = {
  thickness = { type = "number", default = 0.3, above = 0 },
}

-- Blames the generator's caller: level 3 from the generator itself (fail ->
-- generator -> caller), 4 from resolve.
local function fail(message, level)
  error(GENERATOR .. ": " .. message, level or 3)
end

-- Fills in the arch's dimensions (as models.arch does) and checks them.
local function resolve(o, given)
  if o.shape == "semicircular" then
    if given.rise ~= nil then fail("rise: not an option of a semicircular arch (it is span / 2)", 4) end
    o.radius = o.span / 2
    o.rise = o.radius
    if o.thickness >= 2 * o.radius then
      fail(("thickness must be < span (%g), got %g"):format(o.span, o.thickness), 4)
    end
  else
    o.rise = o.rise or ({ segmental = 3 / 8, elliptical = 1 / 3, catenary = 1 / 2 })[o.shape] * o.span
    if o.shape == "segmental" and o.rise >= o.span / 2 then
      fail(("rise: a segmental arch needs rise < span / 2 (%g), got %g"):format(o.span / 2, o.rise), 4)
    end
    if o.thickness >= 2 * o.rise then
      fail(("thickness must be < 2 * rise (%g), got %g"):format(2 * o.rise, o.thickness), 4)
    end
    if o.shape == "elliptical" then
      local a, b = o.span / 2, o.rise
      local limit = 2 * math.min(a * a / b, b * b / a)
      if o.thickness >= limit then
        fail(("thickness must be < 2 * the smallest radius of curvature of the ellipse (%g), got %g")
          :format(limit, o.thickness), 4)
      end
    elseif o.shape == "catenary" then
      local a = arch_shapes.catenary_parameter(o.span, o.rise)
      if o.thickness >= 2 * a then
        fail(("thickness must be < 2 * the catenary's radius of curvature at the crown (%g), got %g")
          :format(2 * a, o.thickness), 4)
      end
    end
  end
  o.joints = "radial"
end

return function(opts)
  local given = {}
  if type(opts) == "table" then
    for key, value in pairs(opts) do given[key] = value end
  else
    given = opts -- options.check reports it
  end
  local deck
  if type(given) == "table" then deck, given.deck = given.deck, nil end
  local o = options.check(GENERATOR, given, spec)
  options.limit_blocks(GENERATOR, o.spans * (2 * o.voussoirs + o.pier_courses),
    ("spans = %d with voussoirs = %d and pier_courses = %d"):format(o.spans, o.voussoirs, o.pier_courses))
  resolve(o, given or {})
  -- deck: true / false, or a table of deck options; without spandrels there
  -- is nothing level to carry it, so it defaults to false there.
  if deck == nil then deck = o.spandrel end
  if type(deck) == "table" then
    deck = options.check(GENERATOR .. ": deck", deck, deck_spec)
  elseif deck == true then
    deck = { thickness = deck_spec.thickness.default }
  elseif deck ~= false then
    fail(("deck: expected a boolean or a table, got %s"):format(type(deck)))
  end
  if deck and not o.spandrel then
    fail("deck needs spandrel = true (the deck rests on the spandrel walls)")
  end
  if o.cover ~= nil and not o.spandrel then
    fail("cover: only with spandrel = true")
  end
  local cover = o.cover or o.thickness / 2

  -- arch_shapes reports a degenerate voussoir from shapes.joints (via
  -- check_section): error level 5 blames the generator's caller.
  local joints = arch_shapes.joints(o, function(message) error(GENERATOR .. ": " .. message, 5) end)
  local n = o.voussoirs
  local clear = -2 * joints[0].ix              -- between the intrados springings
  local spring = joints[0].ix - joints[0].ex   -- length of a springing joint (on z = 0)
  if o.pier_width <= 2 * spring then
    fail(("pier_width must be > the two springing joints' length (%g), got %g"):format(2 * spring, o.pier_width))
  end
  if o.abutment_width <= spring then
    fail(("abutment_width must be > the springing joint's length (%g), got %g"):format(spring, o.abutment_width))
  end
  local top = 0 -- highest extrados point
  for k = 0, n do top = math.max(top, joints[k].ez) end
  local H = top + cover                         -- deck level (top of the spandrels)
  local pitch = clear + o.pier_width
  local y0, y1 = -o.depth / 2, o.depth / 2
  local h = o.pier_height
  local density = o.density

  -- A prism along y over a section given counter-clockwise or not in x-z.
  local function prism(section)
    local polygon = {}
    for i, p in ipairs(section) do polygon[i] = { p[1], y0, p[2] } end
    return ashlar.prism(polygon, { 0, o.depth, 0 }, { density = density })
  end
  local function box(xa, xb, za, zb)
    return prism{ { xa, za }, { xb, za }, { xb, zb }, { xa, zb } }
  end

  local s = ashlar.structure()
  local centres = {}
  for p = 1, o.spans do centres[p] = (p - (o.spans + 1) / 2) * pitch end
  local level = {} -- blocks of the level z = H from left to right, as { x0, x1 }

  -- Arches and their spandrels, span by span.
  local spandrels = {}
  for p, x in ipairs(centres) do
    for k = 1, n do
      s:add(arch_shapes.voussoir(joints[k - 1], joints[k], x, 0, y0, y1, density),
            { name = ("span %d voussoir %d"):format(p, k) })
    end
    spandrels[p] = {}
    if o.spandrel then
      for k = 1, n do
        local a, b = joints[k - 1], joints[k]
        spandrels[p][k] = prism{ { x + a.ex, a.ez }, { x + b.ex, b.ez }, { x + b.ex, H }, { x + a.ex, H } }
      end
    end
  end
  for p, x in ipairs(centres) do
    for k, block in ipairs(spandrels[p]) do
      s:add(block, { name = ("spandrel %d %d"):format(p, k) })
    end
  end

  -- Piers (courses from the bottom) and their fills.
  for p = 1, o.spans - 1 do
    local xa, xb = centres[p] + clear / 2, centres[p + 1] - clear / 2
    for c = 1, o.pier_courses do
      local z0, z1 = -h + (c - 1) * h / o.pier_courses, -h + c * h / o.pier_courses
      if c == o.pier_courses then z1 = 0 end
      s:add(box(xa, xb, z0, z1), { name = ("pier %d course %d"):format(p, c) })
    end
  end
  if o.spandrel then
    for p = 1, o.spans - 1 do
      s:add(box(centres[p] + joints[n].ex, centres[p + 1] + joints[0].ex, 0, H),
            { name = ("pier %d fill"):format(p) })
    end
  end

  -- Abutments: L-shaped with spandrels (up to H outside the extrados
  -- springing), boxes up to z = 0 without.
  local xi, xe = centres[1] + joints[0].ix, centres[1] + joints[0].ex
  local xa = xi - o.abutment_width
  if o.spandrel then
    s:add(prism{ { xa, -h }, { xi, -h }, { xi, 0 }, { xe, 0 }, { xe, H }, { xa, H } }, { name = "abutment left" })
    s:add(prism{ { -xa, -h }, { -xa, H }, { -xe, H }, { -xe, 0 }, { -xi, 0 }, { -xi, -h } }, { name = "abutment right" })
  else
    s:add(box(xa, xi, -h, 0), { name = "abutment left" })
    s:add(box(-xi, -xa, -h, 0), { name = "abutment right" })
  end

  -- Deck: one slab over each block of the level z = H, left to right.
  if deck then
    level[#level + 1] = { xa, xe }
    for p, x in ipairs(centres) do
      for k = 1, n do level[#level + 1] = { x + joints[k - 1].ex, x + joints[k].ex } end
      if p < o.spans then level[#level + 1] = { x + joints[n].ex, centres[p + 1] + joints[0].ex } end
    end
    level[#level + 1] = { -xe, -xa }
    for i, piece in ipairs(level) do
      s:add(box(piece[1], piece[2], H, H + deck.thickness), { name = ("deck %d"):format(i) })
    end
  end

  -- Ground under everything, as thick as the arch ring.
  s:add(box(xa, -xa, -h - o.thickness, -h), { support = true, name = "ground" })
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
