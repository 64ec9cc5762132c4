-- models.wall: a brick wall on a ground slab, in the x-z plane (length along
-- x, thickness along y), in running or stack bond.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local spec = {
  length = { type = "number", default = 4.8, above = 0 },     -- m
  height = { type = "number", default = 0.7, above = 0 },     -- m
  thickness = { type = "number", default = 0.11, above = 0 }, -- m
  brick = { type = "vec2", default = { 0.24, 0.07 }, above = 0 }, -- {length, height}, m
  bond = { type = "string", default = "running", one_of = { "running", "stack" } },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
  ground = { type = "boolean", default = true },              -- add a support slab below
}

-- Whole multiples only: a wall of 4.81 m with 0.24 m bricks is a mistake.
local function count(generator_key, total, unit)
  local n = math.floor(total / unit + 0.5)
  if n < 1 or math.abs(n * unit - total) > 1e-9 * total then
    error(("models.wall: %s %g is not a whole number of bricks of %g"):format(generator_key, total, unit), 3)
  end
  return n
end

return function(opts)
  local o = options.check("models.wall", opts, spec)
  local l, h, t = o.brick[1], o.brick[2], o.thickness
  local per_course = count("length", o.length, l)
  local courses = count("height", o.height, h)
  options.limit_blocks("models.wall", per_course * courses,
    ("%.0f bricks per course x %.0f courses"):format(per_course, courses))
  local s = ashlar.structure()
  if o.ground then
    s:add(ashlar.box{ size = { o.length + 2 * h, t + 2 * h, h }, center = { o.length / 2, 0, -h / 2 },
                      density = o.density }, { support = true, name = "ground" })
  end
  for c = 1, courses do
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
    for i = 1, #joints - 1 do
      local x0, x1 = joints[i], joints[i + 1]
      s:add(ashlar.box{ size = { x1 - x0, t, h }, center = { (x0 + x1) / 2, 0, (c - 0.5) * h },
                        density = o.density }, { name = ("course %d brick %d"):format(c, i) })
    end
  end
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
