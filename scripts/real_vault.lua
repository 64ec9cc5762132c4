-- The Armadillo vault (tests/data/compas_cra/armadillo_cra.json: 399
-- voussoirs, 33 supports, warped faces; it was built and stood) through
-- contact detection at tolerances 1 to 6 cm and with the file's own
-- interfaces: interfaces found, overlaps refused, and the verdict of the
-- equilibrium method (friction 0.84), with times.
--
--   build/bin/ashlar scripts/real_vault.lua [methods...]
-- methods: any of equilibrium (default), kinematic, cra.
local ashlar = require "ashlar"

local path = "tests/data/compas_cra/armadillo_cra.json"
local methods = { ... }
if #methods == 0 then methods = { "equilibrium" } end

local function verdict(s, method, tolerance)
  local t = ashlar.clock()
  local ok, r = pcall(ashlar.analyze, s, { friction = 0.84, contact_tolerance = tolerance, method = method })
  if not ok then return (tostring(r):gsub("\n.*", ""):sub(1, 90)), ashlar.clock() - t end
  return ("%s (infeasibility %.3g, %s)"):format(r.stable and "stands" or "falls", r.infeasibility, r.status),
    ashlar.clock() - t
end

local t = ashlar.clock()
local detected = ashlar.import(path, { planarity = 0.05, interfaces = "detect" })
print(("%d blocks, imported in %.2f s"):format(#detected, ashlar.clock() - t))
for _, tolerance in ipairs{ 0.01, 0.02, 0.03, 0.04, 0.05, 0.06 } do
  local count = #detected:interfaces{ tolerance = tolerance }
  for _, method in ipairs(methods) do
    local text, seconds = verdict(detected, method, tolerance)
    print(("tolerance %.2f m: %4d interfaces, %s: %s, %.2f s"):format(tolerance, count, method, text, seconds))
  end
end
local stored = ashlar.import(path, { planarity = 0.05 })
for _, method in ipairs(methods) do
  local text, seconds = verdict(stored, method, 0.04)
  print(("the file's %d interfaces, %s: %s, %.2f s"):format(#stored:interfaces(), method, text, seconds))
end
