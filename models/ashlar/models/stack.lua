-- models.stack: equal boxes stacked one on another, each shifted along x
-- relative to the one below, on a ground slab: the overhang problem. Block 1
-- is centred on the z axis with its base at z = 0.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local spec = {
  blocks = { type = "number", default = 5, integer = true, min = 1 },
  size = { type = "vec3", default = { 1, 1, 0.5 }, above = 0 },  -- {x, y, z}, m
  offset = { type = "number", default = 0.1 },   -- m, every block relative to the one below
  offsets = { type = "table" },                  -- or one offset per block above the first
  density = { type = "number", default = 2400, above = 0 },   -- kg/m^3
  ground = { type = "boolean", default = true },              -- add a support slab below
}

return function(opts)
  local o = options.check("models.stack", opts, spec)
  local n, b = o.blocks, o.size[1]
  local offsets = {}
  if o.offsets ~= nil then
    if opts.offset ~= nil then
      error("models.stack: give either offset or offsets, not both", 2)
    end
    if #o.offsets ~= n - 1 then
      error(("models.stack: offsets: expected %d numbers (one per block above the first), got %d")
        :format(n - 1, #o.offsets), 2)
    end
    for i = 1, n - 1 do offsets[i] = o.offsets[i] end
  else
    for i = 1, n - 1 do offsets[i] = o.offset end
  end
  for i = 1, n - 1 do
    local d = offsets[i]
    local where = o.offsets ~= nil and ("offsets[%d]"):format(i) or "offset"
    if type(d) ~= "number" or d ~= d or d == math.huge or d == -math.huge then
      error(("models.stack: %s: expected a finite number"):format(where), 2)
    end
    -- A block shifted by its whole width or more would not touch the one below.
    if math.abs(d) >= b then
      error(("models.stack: %s: must be smaller in magnitude than the block width size[1] = %g, got %g"):format(where, b, d), 2)
    end
  end
  local s = ashlar.structure()
  local x = 0
  for i = 1, n do
    if i > 1 then x = x + offsets[i - 1] end
    s:add(ashlar.box{ size = o.size, center = { x, 0, (i - 0.5) * o.size[3] }, density = o.density },
          { name = ("block %d"):format(i) })
  end
  if o.ground then
    -- Twice block 1's footprint: it touches block 1 only.
    s:add(ashlar.box{ size = { 2 * b, 2 * o.size[2], o.size[3] }, center = { 0, 0, -o.size[3] / 2 },
                      density = o.density }, { support = true, name = "ground" })
  end
  -- An extrusion along y with no out-of-plane load: in-plane equations suffice.
  s:set_planar(true)
  return s
end
