-- The least friction coefficient with which an H frame stands when its beam
-- is wedged between the posts (models.h_frame{ beam = "between" }, the
-- defaults: 5 courses, posts 0.4 wide, 3 high, 1.2 apart), from
-- ashlar.friction_demand.
--
-- Reference, by hand (tests/lua/small_models_spec.lua): the beam's weight W
-- reaches each post as friction V = W / 2, which needs a thrust
-- N >= V / mu; each post's joints must then neither slide nor tip outwards.
-- The binding joint gives mu = 1.125 for these dimensions.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local check = require "ashlar.regression"

local demand = ashlar.friction_demand(models.h_frame{ beam = "between" }, { tolerance = 1e-9 })
check("status", demand.status, { reference = "optimal" })
-- Each program's verdict is resolved to the solver's tolerance, hence the
-- looser tolerances than the bracket's 1e-9.
check("friction demand", demand.friction, { tolerance = 1e-7, reference = 1.125, reference_tolerance = 1e-6 })
