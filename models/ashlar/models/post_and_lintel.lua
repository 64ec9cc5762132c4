-- models.post_and_lintel: a horizontal bar (the lintel) on two or more posts
-- of different widths standing on a ground slab, in the x-z plane: the
-- thesis's figure 14 (there three posts, the leftmost thin, the middle one
-- thicker). Posts are placed from left to right with `span` clear between
-- neighbours, or `spans[i]` between posts i and i + 1; the posts and the lintel are centred on x = 0 and y = 0, the
-- ground's top is z = 0. The lintel is at least as long as the posts and
-- openings together, and posts are as deep as the lintel, so every post's
-- top is a whole face of contact with the lintel.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local G = "models.post_and_lintel"

local spec = {
  span = { type = "number", above = 0 },                     -- m, clear opening between neighbouring posts; 1.5
  spans = { type = "table" },                                -- m, one opening per pair of neighbours, instead of span
  -- {length, depth, height}, m; the length defaults to the posts' extent.
  lintel = { type = "vec3", above = 0 },
  -- Figure 14's three posts: thin on the left, thickest in the middle.
  posts = { type = "table", default = { { width = 0.3, height = 2 }, { width = 0.9, height = 2 },
                                        { width = 0.6, height = 2 } } },
  density = { type = "number", default = 2400, above = 0 },  -- kg/m^3
}

local post_spec = {
  width = { type = "number", default = 0.4, above = 0 },     -- m, along x
  height = { type = "number", default = 2, above = 0 },      -- m
}

local function post_name(i, n)
  if i == 1 then return "post left" end
  if i == n then return "post right" end
  return ("post %d"):format(i)
end

return function(opts)
  local o = options.check(G, opts, spec)
  local n = #o.posts
  if n < 2 then
    error(("%s: posts: expected at least 2 posts, got %d"):format(G, n), 2)
  end
  local posts = {}
  for i = 1, n do
    -- Called from here so that errors blame the generator's caller.
    posts[i] = options.check(("%s: posts[%d]"):format(G, i), o.posts[i], post_spec)
  end
  local height = posts[1].height
  for i = 2, n do
    if posts[i].height ~= height then
      error(("%s: posts[%d]: height %g differs from posts[1]'s %g (the lintel is horizontal)")
        :format(G, i, posts[i].height, height), 2)
    end
  end
  if o.span and o.spans then error(("%s: give span or spans, not both"):format(G), 2) end
  local spans = {}
  if o.spans then
    if #o.spans ~= n - 1 then
      error(("%s: spans: expected %d openings (one per pair of neighbouring posts), got %d"):format(G, n - 1, #o.spans), 2)
    end
    for i = 1, n - 1 do
      local v = o.spans[i]
      if type(v) ~= "number" or not (v > 0) or v == math.huge then
        error(("%s: spans[%d]: expected a finite number > 0, got %s"):format(G, i, tostring(v)), 2)
      end
      spans[i] = v
    end
  else
    for i = 1, n - 1 do spans[i] = o.span or 1.5 end
  end
  local extent = 0
  for i = 1, n - 1 do extent = extent + spans[i] end
  for i = 1, n do extent = extent + posts[i].width end
  local lintel = o.lintel or { extent, 0.5, 0.5 }
  if lintel[1] < extent then
    error(("%s: lintel[1] (length) must be >= %g, the posts and openings together, got %g")
      :format(G, extent, lintel[1]), 2)
  end
  local depth = lintel[2]
  local s = ashlar.structure()
  s:add(ashlar.box{ size = lintel, center = { 0, 0, height + lintel[3] / 2 }, density = o.density },
        { name = "lintel" })
  local x = -extent / 2
  for i = 1, n do
    local w = posts[i].width
    s:add(ashlar.box{ size = { w, depth, height }, center = { x + w / 2, 0, height / 2 }, density = o.density },
          { name = post_name(i, n) })
    x = x + w + (spans[i] or 0)
  end
  -- Reaches past the outer posts by the lintel's height; touches only the posts.
  local t = lintel[3]
  s:add(ashlar.box{ size = { extent + 2 * t, depth + 2 * t, t }, center = { 0, 0, -t / 2 }, density = o.density },
        { support = true, name = "ground" })
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
