-- models.perturbed(s, opts): an imperfect copy of a structure, as CAD
-- exports, remeshed surfaces and scans deliver models. Every vertex of every
-- free block moves by a random vector of length up to `amount` times its
-- block's size (bounding-box diagonal), uniform in the ball, each block on
-- its own: faces warp, and joints open or interpenetrate, by that order.
-- Supports stay as they are. Names, supports, loads and the planar flag
-- carry over; blocks are made with `planarity` (warped faces accepted). The
-- same seed gives the same copy, whatever else uses math.random.
local ashlar = require "ashlar"
local options = require "ashlar.models.options"

local spec = {
  amount = { type = "number", default = 0.01, min = 0, max = 0.1 },   -- of each block's size
  seed = { type = "number", default = 1, integer = true, min = 0 },
  planarity = { type = "number", default = 0.05, min = 0, max = 0.2 },  -- see ashlar.block
}

-- A 64-bit linear congruential generator (Knuth's MMIX constants): uniform
-- numbers in [0, 1) from its top 53 bits.
local function generator(seed)
  local state = seed * 2 + 1
  return function()
    state = state * 6364136223846793005 + 1442695040888963407
    return (state >> 11) * 2.0 ^ -53
  end
end

local function block_size(b)
  local lo, hi = b:bounds()
  return math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
end

return function(s, opts)
  local meta = getmetatable(s)
  -- The type name: the metatable's __name, or the metatable itself in a sandbox.
  if meta ~= "ashlar.Structure" and not (type(meta) == "table" and meta.__name == "ashlar.Structure") then
    error("models.perturbed: expected a structure as the first argument, got " .. type(s), 2)
  end
  local o = options.check("models.perturbed", opts, spec)
  if #s:cables() > 0 then
    error("models.perturbed: structures with cables are not supported (their end points would not follow)", 2)
  end
  for _, c in ipairs(s:interfaces()) do
    if c.explicit then
      error("models.perturbed: structures with explicit interfaces are not supported (their polygons would not follow)", 2)
    end
  end
  local random = generator(o.seed)
  -- A point uniform in the ball of radius `length`, by rejection.
  local function move(length)
    while true do
      local v = { 2 * random() - 1, 2 * random() - 1, 2 * random() - 1 }
      local r2 = v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2
      if r2 <= 1 then return { v[1] * length, v[2] * length, v[3] * length } end
    end
  end
  local out = ashlar.structure()
  for i = 1, #s do
    local b = s:block(i)
    local vertices = b:vertices()
    if not s:is_support(i) then
      local length = o.amount * block_size(b)
      for _, p in ipairs(vertices) do
        local d = move(length)
        for k = 1, 3 do p[k] = p[k] + d[k] end
      end
    end
    out:add(ashlar.block{ vertices = vertices, faces = b:faces(), density = b:density(), name = b:name(),
                          planarity = math.max(o.planarity, b:planarity()) },
            { support = s:is_support(i), name = s:name(i) })
  end
  for _, load in ipairs(s:loads()) do out:add_load(load) end
  out:set_planar(s:is_planar())
  return out
end
