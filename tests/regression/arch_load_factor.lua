-- Load factors (a horizontal body force, as a multiple of each voussoir's
-- weight) of 64-voussoir semicircular arches, R = 1, without sliding:
-- ashlar.load_factor's linear program, the static theorem.
--
-- References: the kinematic theorem's minimum over every four-hinge
-- mechanism, an independent search (tests/lua/four_hinge.lua,
-- scripts/stability_margins.lua), which also says that collapse opens four
-- hinges.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local check = require "ashlar.regression"

local four_hinge_factor = { [0.15] = 0.1446973, [0.20] = 0.2839374, [0.30] = 0.5182635 }

for _, ratio in ipairs{ 0.15, 0.20, 0.30 } do
  local f = ashlar.load_factor(models.arch{ radius = 1, thickness = ratio, voussoirs = 64 },
                               { friction = math.huge })
  local name = ("t/R %.2f: "):format(ratio)
  check(name .. "status", f.status, { reference = "optimal" })
  -- The references have 7 significant digits.
  check(name .. "load factor", f.factor, { reference = four_hinge_factor[ratio], reference_tolerance = 1e-6 })
  check(name .. "hinges", #f.limit, { reference = 4, reference_absolute = 0 })
end
