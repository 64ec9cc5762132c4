-- A block b wide and h high on a table: tipping, sliding and the tilt-table
-- test, each a load factor with a closed form.
--
-- A lateral body force lambda W tips the block over its edge when the
-- resultant passes the edge: lambda = b / h. It slides first when the
-- friction coefficient mu < b / h: lambda = mu (the friction pyramid has an
-- edge along the load). Tilted by theta towards the load (ashlar.tilt),
-- gravity already leans by theta, so what remains is tan(atan(b / h) - theta)
-- for tipping and tan(atan(mu) - theta) for sliding.
local ashlar = require "ashlar"
local check = require "ashlar.regression"

local function block_on_table(b, h)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { b, 0.8, h }, center = { 0, 0, h / 2 } }, { name = "block" })
  s:add(ashlar.box{ size = { 2, 1.5, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "table" })
  return s
end

local NO_SLIDING = { friction = math.huge }
local CLOSED_FORM = 1e-9  -- relative: a linear program, solved to round-off

local slender = block_on_table(0.4, 1.0)
check("tipping: b/h 0.4", ashlar.load_factor(slender, NO_SLIDING).factor,
      { reference = 0.4, reference_tolerance = CLOSED_FORM })

local squat = block_on_table(0.6, 1.0)
check("sliding: mu 0.3 < b/h 0.6", ashlar.load_factor(squat, { friction = 0.3 }).factor,
      { reference = 0.3, reference_tolerance = CLOSED_FORM })

local theta = 0.2
check("tilted 0.2 rad: tipping", ashlar.load_factor(ashlar.tilt(slender, theta), NO_SLIDING).factor,
      { reference = math.tan(math.atan(0.4) - theta), reference_tolerance = CLOSED_FORM })
check("tilted 0.2 rad: sliding, mu 0.5", ashlar.load_factor(ashlar.tilt(squat, theta), { friction = 0.5 }).factor,
      { reference = math.tan(math.atan(0.5) - theta), reference_tolerance = CLOSED_FORM })
