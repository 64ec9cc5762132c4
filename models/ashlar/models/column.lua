-- models.column: a column of equal box drums standing on a ground slab,
-- centred on the z axis with its base at z = 0.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local spec = {
  height = { type = "number", default = 3, above = 0 },       -- m, all drums together
  width = { type = "number", default = 0.5, above = 0 },      -- m, along x
  depth = { type = "number", default = 0.5, above = 0 },      -- m, along y
  drums = { type = "number", default = 6, integer = true, min = 1 },
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
  ground = { type = "boolean", default = true },              -- add a support slab below
}

return function(opts)
  local o = options.check("models.column", opts, spec)
  local h = o.height / o.drums
  local s = ashlar.structure()
  -- Drums first, so that drum i is block i, counted from the bottom.
  for i = 1, o.drums do
    s:add(ashlar.box{ size = { o.width, o.depth, h }, center = { 0, 0, (i - 0.5) * h }, density = o.density },
          { name = ("drum %d"):format(i) })
  end
  if o.ground then
    -- Twice the column's footprint, as thick as half its smaller side.
    local t = math.min(o.width, o.depth) / 2
    s:add(ashlar.box{ size = { 2 * o.width, 2 * o.depth, t }, center = { 0, 0, -t / 2 }, density = o.density },
          { support = true, name = "ground" })
  end
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
