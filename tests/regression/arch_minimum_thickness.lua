-- Minimum thickness of semicircular arches (radial joints, no sliding), as
-- t/R, from Heyman's geometric factor search over ashlar.analyze.
--
-- References: the thrust-line minimum of the same polyhedral arch (straight
-- intrados and extrados chords), a small linear program in the crown thrust
-- solved independently in tests/lua/edge_cases.lua (arch_threshold). They
-- sit just below the values for voussoirs bounded by circular arcs
-- (0.1009, 0.1072, 0.1074, docs/verification.md): the chords move the weight inwards. With
-- 512 voussoirs it approaches Milankovitch's 0.1075 for the continuous arch.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local check = require "ashlar.regression"

local thrust_line_minimum = {
  [8] = 0.099971674047, [16] = 0.107076200973, [64] = 0.107383202503, [512] = 0.107477864418,
}

for _, voussoirs in ipairs{ 8, 16, 64, 512 } do
  local search = ashlar.geometric_factor(function(t)
    return models.arch{ radius = 1, thickness = t, voussoirs = voussoirs }
  end, 0.15, { friction = math.huge, tolerance = 1e-8 })
  check(("%d voussoirs: search status"):format(voussoirs), search.status, { reference = "converged" })
  -- The search brackets the verdict of each analysis, which is resolved to
  -- the solver's tolerance: the last digits may move between machines.
  check(("%d voussoirs: t/R"):format(voussoirs), search.minimum, {
    tolerance = 1e-7,
    reference = thrust_line_minimum[voussoirs], reference_tolerance = 1e-6,
  })
end
