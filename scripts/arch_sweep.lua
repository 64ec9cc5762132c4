-- The arch sweep of the studies guide: 121 thicknesses × 3 voussoir counts
-- × 2 friction coefficients (726 analyses), kept in SQLite, resumable.
--   build/bin/ashlar scripts/arch_sweep.lua [db] [workers] [csv] [thicknesses]
--   mpirun -np 4 build/bin/ashlar scripts/arch_sweep.lua [db] [workers] [csv] [thicknesses]
-- `thicknesses` (default 121) makes a coarser sweep of the same range.
-- Prints one line, "runs <n> seconds <s> runs_per_second <r> workers <w>".
local ashlar = require "ashlar"
local models = require "ashlar.models"

local db, workers, csv = arg[1] or "arch.sqlite", tonumber(arg[2] or "0"), arg[3] or "arch.csv"
local thicknesses = math.tointeger(tonumber(arg[4] or "121"))
assert(thicknesses and thicknesses >= 2, "arch_sweep.lua: thicknesses (argument 4) must be an integer of at least 2")

local study = ashlar.study{
  name = "arch-thickness",
  params = { t = ashlar.range(0.08, 0.20, thicknesses), n = { 16, 32, 64 }, mu = { 0.5, 0.7 } },
  run = function(p)
    local s = models.arch{ radius = 1, thickness = p.t, voussoirs = p.n }
    local r = ashlar.analyze(s, { friction = p.mu })
    return { stable = r.stable, infeasibility = r.infeasibility }
  end,
  db = db, workers = workers,
}
study:csv(csv)
if ashlar.rank() == 0 then
  local info = study:info()
  print(("runs %d seconds %.3f runs_per_second %.1f workers %d errors %d"):format(
    info.ran, info.seconds, info.runs_per_second, info.workers, info.errors))
end
