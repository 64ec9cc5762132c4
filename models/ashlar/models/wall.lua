-- models.wall: a brick wall on a ground slab, in the x-z plane (length along
-- x, thickness along y), in running or stack bond, with openings (windows
-- and doors) under lintels or voussoir arches.
--
-- Openings keep to the bond: jambs on half-brick lines, sills and heads on
-- course lines, so the courses beside an opening end at its jambs with a
-- whole or a half brick, as they do at the wall's ends. A lintel is one
-- block over the opening and a bearing on each side, in place of the bricks
-- there. An arch head is a ring of voussoirs (ashlar.models.arch_shapes)
-- springing from the tops of the jambs; the bricks of the courses it rises
-- into are cut along its extrados chords, so each rests on the voussoirs'
-- faces (prisms along y over the cut section).
local ashlar = require "ashlar"
local options = require "ashlar.models.options"
local arch_shapes = require "ashlar.models.arch_shapes"

local G = "models.wall"

local spec = {
  length = { type = "number", default = 4.8, above = 0 },     -- m
  height = { type = "number", default = 0.7, above = 0 },     -- m
  thickness = { type = "number", default = 0.11, above = 0 }, -- m
  brick = { type = "vec2", default = { 0.24, 0.07 }, above = 0 }, -- {length, height}, m
  bond = { type = "string", default = "running", one_of = { "running", "stack" } },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
  ground = { type = "boolean", default = true },              -- add a support slab below
  openings = { type = "table" },                              -- a list of opening_spec tables
}

-- One opening; lengths in m. Defaults that depend on the brick are filled in
-- by the generator (nil here).
local opening_spec = {
  x = { type = "number", min = 0 },          -- left jamb, from the wall's left end
  width = { type = "number", above = 0 },    -- between the jambs
  sill = { type = "number", default = 0, min = 0 }, -- height of the opening's bottom; 0: a door
  height = { type = "number", above = 0 },   -- of the jambs: sill to lintel or springing
  head = { type = "string", default = "lintel", one_of = { "lintel", "arch" } },
  bearing = { type = "number", above = 0 },  -- lintel: on each side; default one brick length
  lintel_height = { type = "number", above = 0 }, -- lintel: default two courses
  rise = { type = "number", above = 0 },     -- arch: of the intrados; default width / 2 (semicircular)
  ring = { type = "number", above = 0 },     -- arch: ring thickness, radial; default one brick length
  voussoirs = { type = "number", integer = true, min = 2 }, -- arch: default one course height each at the intrados
}

-- `value` as a whole number of `unit`s (a wall of 4.81 m with 0.24 m bricks
-- is a mistake), or nil.
local function whole(value, unit)
  local n = math.floor(value / unit + 0.5)
  if math.abs(n * unit - value) > 1e-9 * math.max(value, unit) then return nil end
  return n
end

-- Whole multiples only; level 3 blames the generator's caller.
local function count(key, total, unit)
  local n = whole(total, unit)
  if not n or n < 1 then
    error(("%s: %s %g is not a whole number of bricks of %g"):format(G, key, total, unit), 3)
  end
  return n
end

-- The extrados of an arch head as a chain of points { x, z } from the left
-- springing to the right one, and its height above x (nil off the chain).
local function extrados_height(chain, x)
  if x < chain[1][1] or x > chain[#chain][1] then return nil end
  for k = 2, #chain do
    local p, q = chain[k - 1], chain[k]
    if x <= q[1] then return p[2] + (q[2] - p[2]) * (x - p[1]) / (q[1] - p[1]) end
  end
end

-- Where a chain crosses the height `level`: a list of { x, rising }.
local function crossings(chain, level)
  local found = {}
  for k = 2, #chain do
    local p, q = chain[k - 1], chain[k]
    if (p[2] - level) * (q[2] - level) < 0 then
      found[#found + 1] = { p[1] + (level - p[2]) * (q[1] - p[1]) / (q[2] - p[2]), q[2] > p[2] }
    end
  end
  return found
end

-- The parts of the box [a, b] x [z0, z1] above every chain (the extrados
-- of the arch heads) as sections, lists of { x, z }: one per stretch of x
-- where the box is not wholly under a chain. The lower edge follows the
-- chords through their vertices and the points where they cross z0 and z1,
-- so a part meets each voussoir along a piece of its extrados face.
local function above_chains(a, b, z0, z1, chains)
  -- Points of the lower edge { x, height where known exactly }; within
  -- 1e-9 of the brick of one another they are one (a brick's end wins: a
  -- springing on a joint's line is on it).
  local points = { { a, nil, true }, { b, nil, true } }
  for _, chain in ipairs(chains) do
    for _, p in ipairs(chain) do
      if p[1] > a - 1e-9 * (b - a) and p[1] < b + 1e-9 * (b - a) then
        points[#points + 1] = { p[1], math.max(z0, p[2]) }
      end
    end
    for _, level in ipairs{ z0, z1 } do
      for _, crossing in ipairs(crossings(chain, level)) do
        if crossing[1] > a and crossing[1] < b then points[#points + 1] = { crossing[1], level } end
      end
    end
  end
  table.sort(points, function(p, q) return p[1] < q[1] end)
  local xs, g = {}, {}
  for _, p in ipairs(points) do
    local last = #xs
    if last > 0 and p[1] - xs[last] <= 1e-9 * (b - a) then
      if p[3] then xs[last] = p[1] end
      g[last] = g[last] or p[2]
    elseif p[1] >= a and p[1] <= b then
      xs[last + 1], g[last + 1] = p[1], p[2]
    end
  end
  for i, x in ipairs(xs) do
    if not g[i] then
      g[i] = z0
      for _, chain in ipairs(chains) do g[i] = math.max(g[i], extrados_height(chain, x) or z0) end
    end
  end
  local parts, part = {}, nil
  for i = 1, #xs - 1 do
    if xs[i + 1] > xs[i] and (g[i] + g[i + 1]) / 2 < z1 then
      if not part then
        part = { { xs[i], z1 } }
        if g[i] < z1 then part[#part + 1] = { xs[i], g[i] } end
        parts[#parts + 1] = part
      elseif not (g[i - 1] == z0 and g[i] == z0 and g[i + 1] == z0) then
        part[#part + 1] = { xs[i], g[i] } -- a corner of the lower edge
      end
      if i + 1 == #xs or not ((g[i + 1] + g[i + 2]) / 2 < z1) then
        part[#part + 1] = { xs[i + 1], g[i + 1] }
        if g[i + 1] < z1 then part[#part + 1] = { xs[i + 1], z1 } end
        part = nil
      end
    end
  end
  return parts
end

return function(opts)
  local o = options.check(G, opts, spec)
  local l, h, t = o.brick[1], o.brick[2], o.thickness
  local per_course = count("length", o.length, l)
  local courses = count("height", o.height, h)
  options.limit_blocks(G, per_course * courses,
    ("%.0f bricks per course x %.0f courses"):format(per_course, courses))
  local y0, y1 = -t / 2, t / 2
  -- The half-brick line at x (checked to be one): the very value of the
  -- course joints there, (i + 0.5) * l or i * l.
  local function on_grid(x) return whole(x, l / 2) * l / 2 end

  -- Openings: checked, then each with its footprint { left, right } (jambs
  -- and head), its courses (integers: the opening spans courses c with
  -- sill < c <= top; a lintel top < c <= head), and an arch's joints.
  local openings = {}
  for key in pairs(o.openings or {}) do
    if math.type(key) ~= "integer" or key < 1 or key > #o.openings then
      error(("%s: openings: expected a list of opening tables { x = ..., width = ..., height = ... }, got the key %s")
        :format(G, tostring(key)), 2)
    end
  end
  for n, given in ipairs(o.openings or {}) do
    local what = ("%s: openings[%d]"):format(G, n)
    local p = options.check(what, given, opening_spec)
    local function fail(message) error(what .. ": " .. message, 3) end
    for _, key in ipairs{ "x", "width", "height" } do
      if p[key] == nil then fail(("%s: required (m)"):format(key)) end
    end
    -- On the bond's grid, and from here on the grid's own values, as the joints.
    for _, rule in ipairs{ { "x", l / 2 }, { "width", l / 2 }, { "bearing", l / 2 }, { "sill", h }, { "height", h },
                           { "lintel_height", h } } do
      local key, unit = rule[1], rule[2]
      if p[key] then
        local steps = whole(p[key], unit)
        if not steps or (key ~= "x" and key ~= "sill" and steps < 1) then
          fail(("%s %g is not a whole number of %s (%g)"):format(key, p[key], unit == h and "courses" or "half bricks",
            unit))
        end
        p[key] = steps * unit
      end
    end
    local lintel_keys, arch_keys = { "bearing", "lintel_height" }, { "rise", "ring", "voussoirs" }
    for _, key in ipairs(p.head == "lintel" and arch_keys or lintel_keys) do
      if p[key] ~= nil then
        fail(("%s: only for head = \"%s\", not \"%s\""):format(key, p.head == "lintel" and "arch" or "lintel", p.head))
      end
    end
    if p.x < l then
      fail(("x %g leaves less than a brick (%g) between the wall's left end and the jamb: the courses "
        .. "there cannot bond"):format(p.x, l))
    end
    if p.x + p.width > o.length - l then
      fail(("x + width %g leaves less than a brick (%g) between the jamb and the wall's right end (%g): the "
        .. "courses there cannot bond"):format(p.x + p.width, l, o.length))
    end
    p.index, p.sill_course, p.top = n, whole(p.sill, h), whole(p.sill + p.height, h)
    local top = p.top * h
    if p.head == "lintel" then
      p.bearing = p.bearing or l
      p.lintel_height = p.lintel_height or 2 * h
      p.left = on_grid(p.x - p.bearing)
      p.right = on_grid(p.x + p.width + p.bearing)
      p.head_course = p.top + whole(p.lintel_height, h)
      p.crown = p.head_course * h
      if p.left < 0 or p.right > o.length then
        fail(("the lintel (bearing %g) reaches beyond the wall's %s end"):format(p.bearing,
          p.left < 0 and "left" or "right"))
      end
    else
      local half, ring = p.width / 2, p.ring or l
      local rise = p.rise or half
      if rise > half * (1 + 1e-9) then
        fail(("rise must be <= width / 2 (%g; a semicircle), got %g"):format(half, rise))
      end
      if rise >= half * (1 - 1e-9) then rise = half end
      -- The intrados is a circle through both jambs' tops, `rise` high.
      local ri = (half * half + rise * rise) / (2 * rise)
      local zc = rise - ri
      local arc = 2 * ri * math.atan(half, -zc)
      local shape = { joints = "radial", thickness = ring,
                      voussoirs = p.voussoirs or math.max(3, math.floor(arc / h + 0.5)) }
      if rise == half then
        shape.shape, shape.radius = "semicircular", half + ring / 2
      else
        local r = ri + ring / 2
        shape.shape, shape.rise, shape.span = "segmental", rise + ring / 2, 2 * math.sqrt(r * r - zc * zc)
      end
      p.joints = arch_shapes.joints(shape, function(message) error(what .. ": " .. message, 5) end)
      p.voussoirs, p.centre, p.springing = shape.voussoirs, (p.x + on_grid(p.x + p.width)) / 2, top
      p.left, p.right = p.centre + p.joints[0].ex, p.centre - p.joints[0].ex
      local chain, crown = {}, top
      for k = 0, p.voussoirs do
        local j = p.joints[k]
        chain[#chain + 1] = { p.centre + j.ex, top + j.ez }
        crown = math.max(crown, top + j.ez)
      end
      p.chain, p.crown = chain, crown
      if p.left < 0 or p.right > o.length then
        fail(("the arch's springing (%g wide beyond the jamb) reaches beyond the wall's %s end")
          :format(-p.joints[0].ex - half, p.left < 0 and "left" or "right"))
      end
    end
    if p.crown > o.height + 1e-9 * o.height then
      fail(("the %s's top (z = %g) is above the wall's (%g)"):format(p.head, p.crown, o.height))
    end
    openings[n] = p
  end
  local by_x = {}
  for n, p in ipairs(openings) do by_x[n] = p end
  table.sort(by_x, function(p, q) return p.x < q.x end)
  for k = 2, #by_x do
    local p, q = by_x[k - 1], by_x[k]
    if q.x < p.x + p.width + l or q.left < p.right then
      error(("%s: openings[%d] (x from %g to %g, with its head %g to %g) and openings[%d] (x from %g to %g, with "
        .. "its head %g to %g) overlap or leave less than a brick (%g) between their jambs")
        :format(G, p.index, p.x, p.x + p.width, p.left, p.right, q.index, q.x, q.x + q.width, q.left, q.right, l), 2)
    end
  end

  local s = ashlar.structure()
  if o.ground then
    s:add(ashlar.box{ size = { o.length + 2 * h, t + 2 * h, h }, center = { o.length / 2, 0, -h / 2 },
                      density = o.density }, { support = true, name = "ground" })
  end
  local function prism(section)
    local polygon = {}
    for i, q in ipairs(section) do polygon[i] = { q[1], y0, q[2] } end
    return ashlar.prism(polygon, { 0, t, 0 }, { density = o.density })
  end
  for c = 1, courses do
    local z0, z1 = (c - 1) * h, c * h
    -- Running bond: every second course starts and ends with a half brick so
    -- that both ends of the wall are flush.
    local joints = {}
    if o.bond == "running" and c % 2 == 0 then
      joints[1] = 0
      for i = 0, per_course - 1 do joints[#joints + 1] = (i + 0.5) * l end
      joints[#joints + 1] = o.length
    else
      for i = 0, per_course do joints[#joints + 1] = i * l end
    end
    -- The stretches of this course taken by openings and lintels (their
    -- ends on half-brick lines cut a brick in two there), and the arch
    -- heads it rises into.
    local holes, chains = {}, {}
    for _, p in ipairs(openings) do
      if c > p.sill_course and c <= p.top then
        holes[#holes + 1] = { p.x, on_grid(p.x + p.width) }
      elseif p.head == "lintel" and c > p.top and c <= p.head_course then
        holes[#holes + 1] = { p.left, p.right }
      elseif p.head == "arch" and c > p.top and z0 < p.crown then
        chains[#chains + 1] = p.chain
      end
    end
    if #holes > 0 then
      for _, hole in ipairs(holes) do
        for _, x in ipairs(hole) do
          local at = on_grid(x)
          local seen = false
          for _, j in ipairs(joints) do seen = seen or math.abs(j - at) <= 1e-9 * l end
          if not seen then joints[#joints + 1] = at end
        end
      end
      table.sort(joints)
    end
    -- A joint just short of where an arch's extrados leaves the course
    -- (less than a quarter brick, on the crown's side) would leave a sliver
    -- of brick there: the brick beyond it reaches to the extrados instead.
    if #chains > 0 then
      local kept = { joints[1] }
      for k = 2, #joints - 1 do
        local j, sliver = joints[k], false
        for _, hole in ipairs(holes) do if j == hole[1] or j == hole[2] then goto keep end end
        for _, chain in ipairs(chains) do
          for _, crossing in ipairs(crossings(chain, z1)) do
            local x, rising = crossing[1], crossing[2]
            sliver = sliver or (rising and j > x - l / 4 and j < x) or (not rising and j > x and j < x + l / 4)
          end
        end
        ::keep::
        if not sliver then kept[#kept + 1] = j end
      end
      kept[#kept + 1] = joints[#joints]
      joints = kept
    end
    local i = 0
    for k = 1, #joints - 1 do
      local x0, x1 = joints[k], joints[k + 1]
      local open = false
      for _, hole in ipairs(holes) do open = open or ((x0 + x1) / 2 > hole[1] and (x0 + x1) / 2 < hole[2]) end
      local cut = false
      for _, chain in ipairs(chains) do cut = cut or (x1 > chain[1][1] and x0 < chain[#chain][1]) end
      if not open and not cut then
        i = i + 1
        s:add(ashlar.box{ size = { x1 - x0, t, h }, center = { (x0 + x1) / 2, 0, (c - 0.5) * h },
                          density = o.density }, { name = ("course %d brick %d"):format(c, i) })
      elseif not open then
        for _, section in ipairs(above_chains(x0, x1, z0, z1, chains)) do
          i = i + 1
          s:add(prism(section), { name = ("course %d brick %d"):format(c, i) })
        end
      end
    end
  end
  -- The heads, opening by opening.
  for n, p in ipairs(openings) do
    if p.head == "lintel" then
      s:add(ashlar.box{ size = { p.right - p.left, t, p.lintel_height },
                        center = { (p.left + p.right) / 2, 0, p.top * h + p.lintel_height / 2 }, density = o.density },
            { name = ("opening %d lintel"):format(n) })
    else
      for k = 1, p.voussoirs do
        s:add(arch_shapes.voussoir(p.joints[k - 1], p.joints[k], p.centre, p.springing, y0, y1, o.density),
              { name = ("opening %d voussoir %d"):format(n, k) })
      end
    end
  end
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
