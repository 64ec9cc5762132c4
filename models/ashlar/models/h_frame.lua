-- models.h_frame: the H-shaped frame of the thesis's figure 10, in the x-z
-- plane: two posts of stacked blocks with a horizontal beam at mid-height
-- between them, on a ground slab. Posts are centred on x = ±(gap + width) / 2,
-- the ground's top is z = 0, everything is centred on y = 0.
--
-- The thesis shows the figure for its load traces ("the weight of the middle
-- block ... is supported equally by the two columns") and gives no
-- dimensions or joints; two readings are offered:
--   beam = "through" (default): the beam runs the whole width, from the
--     outer face of one post to the outer face of the other, in place of the
--     posts' middle course: it rests on the lower halves of the posts, and the
--     upper halves rest on its ends. Every joint is horizontal, so the frame
--     stands under gravity alone.
--   beam = "between": the posts are whole columns and the beam fills the
--     gap between their middle blocks, held only by friction on its two
--     vertical end faces. It stands only if the posts are heavy and wide
--     enough to take the beam's outward thrust (at least W / (2 friction)
--     each), which slender posts are not. With V = W / 2, G the weight of
--     one post block, C courses, the beam in course m = (C + 1) / 2, course
--     height h and post width w, the least friction coefficient is the
--     largest of sqrt(V / ((C - m + 1) G + V)) (sliding under the beam) and
--     V (m - 1 - j) h / ((C - j) G w / 2 + V w) for j = 0 .. m - 2 (the post
--     overturning outwards about joint j, the thrust at the beam's lowest
--     point): 1.125 for the defaults.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local G = "models.h_frame"

local spec = {
  height = { type = "number", default = 3, above = 0 },      -- m, of the posts
  width = { type = "number", default = 0.4, above = 0 },     -- m, of a post along x
  depth = { type = "number", default = 0.4, above = 0 },     -- m, along y, posts and beam
  gap = { type = "number", default = 1.2, above = 0 },       -- m, clear distance between the posts
  -- Courses of height height / courses; odd, so that one is at mid-height (the beam's).
  -- At least 3: a course below the beam and one above.
  courses = { type = "number", default = 5, integer = true, min = 3 },
  beam = { type = "string", default = "through", one_of = { "through", "between" } },
  density = { type = "number", default = 2400, above = 0 },  -- kg/m^3
}

return function(opts)
  local o = options.check(G, opts, spec)
  if o.courses % 2 == 0 then
    error(("%s: courses: must be odd (one course at mid-height for the beam), got %d"):format(G, o.courses), 2)
  end
  local h, w = o.height / o.courses, o.width
  local middle = (o.courses + 1) // 2
  local s = ashlar.structure()
  local function box(size, center) return ashlar.box{ size = size, center = center, density = o.density } end
  -- Posts first, left then right, each from the bottom; the beam's course is
  -- skipped in the "through" reading. Blocks keep their course number.
  for _, side in ipairs{ { -1, "left" }, { 1, "right" } } do
    local x = side[1] * (o.gap + w) / 2
    for c = 1, o.courses do
      if not (o.beam == "through" and c == middle) then
        s:add(box({ w, o.depth, h }, { x, 0, (c - 0.5) * h }), { name = ("post %s %d"):format(side[2], c) })
      end
    end
  end
  local length = o.beam == "through" and o.gap + 2 * w or o.gap
  s:add(box({ length, o.depth, h }, { 0, 0, (middle - 0.5) * h }), { name = "beam" })
  local t = w
  s:add(box({ o.gap + 2 * w + 2 * t, o.depth + 2 * t, t }, { 0, 0, -t / 2 }), { support = true, name = "ground" })
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
