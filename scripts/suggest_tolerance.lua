-- The tolerance report of a structure: ashlar.suggest_tolerance's rows and
-- the range it suggests. Default: the Armadillo vault.
--
--   build/bin/ashlar scripts/suggest_tolerance.lua [model.json]
local ashlar = require "ashlar"

local path = ... or "tests/data/compas_cra/armadillo_cra.json"
local s = ashlar.import(path, { planarity = 0.05, interfaces = "detect" })
local t = ashlar.clock()
local sweep = ashlar.suggest_tolerance(s)
print(("%s: %d blocks, %d tolerances in %.2f s"):format(path, #s, #sweep.rows, ashlar.clock() - t))
print("tolerance (m)\tinterfaces\tpairs\tnew\tlost\toverlaps\tfloating\twarped")
for _, row in ipairs(sweep.rows) do
  print(("%.4g\t%d\t%d\t%d\t%d\t%d\t%d\t%d"):format(row.tolerance, row.interfaces, row.pairs, row.new_pairs,
    row.lost_pairs, row.overlaps, row.floating, row.warped))
end
if sweep.suggested then
  print(("the contacts do not change from %.4g to %.4g m; suggested: %.4g m"):format(sweep.lo, sweep.hi, sweep.suggested))
else
  print("no tolerance gives contacts without overlaps or floating blocks")
end
