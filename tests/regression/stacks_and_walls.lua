-- Stacks of blocks and a brick wall, whose limits follow from statics by
-- hand.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local check = require "ashlar.regression"

local NO_SLIDING = { friction = math.huge }
local CLOSED_FORM = 1e-9

-- Two blocks 1 wide and 0.5 high, the top one shifted 0.45 along +x: it tips
-- over its support's edge when lambda = (0.5 - 0.45) / 0.25.
check("stack of 2, offset 0.45: load factor",
      ashlar.load_factor(models.stack{ blocks = 2, offset = 0.45 }, NO_SLIDING).factor,
      { reference = 0.2, reference_tolerance = CLOSED_FORM })

-- The harmonic stack: block j + 1 shifted b / (2k) beyond block j, with k
-- blocks above that joint, puts every joint exactly at its limit; a little
-- less overhang stands, a little more falls.
local function harmonic(scale)
  local n, offsets = 6, {}
  for j = 1, n - 1 do offsets[j] = scale * 1 / (2 * (n - j)) end
  return models.stack{ blocks = n, size = { 1, 1, 0.3 }, offsets = offsets }
end
check("harmonic stack of 6 at 0.999 of its overhang: stands", ashlar.analyze(harmonic(0.999), NO_SLIDING).stable,
      { reference = true })
check("harmonic stack of 6 at 1.001 of its overhang: stands", ashlar.analyze(harmonic(1.001), NO_SLIDING).stable,
      { reference = false })

-- A wall t thick and H high pushed out of its plane rocks about the outer
-- edge of its lowest bed joint at lambda = t / H (every course is the
-- wall's full thickness), or slides first at lambda = mu when mu < t / H.
local wall = models.wall{ length = 1.2, height = 0.35, thickness = 0.11, bond = "running" }
wall:set_planar(false)  -- the load is out of the x-z plane
local outwards = { 0, 1, 0 }
check("wall 0.11 x 0.35, out of plane: tipping",
      ashlar.load_factor(wall, { direction = outwards, friction = math.huge }).factor,
      { reference = 0.11 / 0.35, reference_tolerance = CLOSED_FORM })
check("wall 0.11 x 0.35, out of plane: sliding, mu 0.2",
      ashlar.load_factor(wall, { direction = outwards, friction = 0.2 }).factor,
      { reference = 0.2, reference_tolerance = 1e-8 })
