-- The margins of semicircular arches (centreline radius R = 1, no sliding
-- unless said): the lateral load factor at t/R = 0.15, 0.2 and 0.3 with 64
-- voussoirs, against the kinematic theorem over every four-hinge mechanism
-- (tests/lua/four_hinge.lua, an independent search), with its time; the
-- friction demand at t/R = 0.12 over the number of voussoirs; and the
-- geometric factor of safety of each arch.
--   ashlar scripts/stability_margins.lua [output folder, default docs/figures]
-- Prints the tables and writes stability_margins.csv in the folder.
local here = arg[0]:match("^(.*)/[^/]*$") or "."
package.path = here .. "/../tests/lua/?.lua;" .. package.path
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"
local four_hinge = require "four_hinge"

local output = arg[1] or "docs/figures"
script_support.make_folders(output)
local VOUSSOIRS = 64
local csv = { "quantity,t_over_R,voussoirs,value,reference,seconds" }

local function arch(ratio, voussoirs)
  return models.arch{ radius = 1, thickness = ratio, voussoirs = voussoirs or VOUSSOIRS }
end

-- Best of five wall times (the first run warms caches).
local function best_time(f)
  local best, value = math.huge, nil
  for _ = 1, 5 do
    local start = ashlar.clock()
    value = f()
    best = math.min(best, ashlar.clock() - start)
  end
  return value, best
end

print(("Lateral load factor, %d voussoirs, no sliding"):format(VOUSSOIRS))
print(("%6s %14s %14s %10s %10s %12s  %s"):format("t/R", "load_factor", "four-hinge", "rel. diff", "LP s",
  "search s", "hinges (joints)"))
for _, ratio in ipairs{ 0.15, 0.2, 0.3 } do
  local s = arch(ratio)
  local f, seconds = best_time(function() return ashlar.load_factor(s, { friction = math.huge }) end)
  local start = ashlar.clock()
  local reference, hinges = four_hinge.collapse_factor(s, VOUSSOIRS)
  local search_seconds = ashlar.clock() - start
  local joints = {}
  for _, h in ipairs(hinges) do joints[#joints + 1] = tostring(h[1]) end
  print(("%6.2f %14.10f %14.10f %10.1e %10.4f %12.1f  %s"):format(ratio, f.factor, reference,
    (f.factor - reference) / reference, seconds, search_seconds, table.concat(joints, ", ")))
  csv[#csv + 1] = ("load_factor,%g,%d,%.12g,%.12g,%.6f"):format(ratio, VOUSSOIRS, f.factor, reference, seconds)
end

print("\nFriction demand at t/R = 0.12 (4-sided pyramid; the arch is planar, so its sides do not matter)")
print(("%9s %12s %9s %10s"):format("voussoirs", "friction", "programs", "seconds"))
for _, n in ipairs{ 16, 32, 64, 128, 256, 512 } do
  local s = arch(0.12, n)
  local d, seconds = best_time(function() return ashlar.friction_demand(s, { tolerance = 1e-9 }) end)
  assert(d.status == "optimal", d.status)
  print(("%9d %12.8f %9d %10.4f"):format(n, d.friction, d.programs, seconds))
  csv[#csv + 1] = ("friction_demand,0.12,%d,%.12g,,%.6f"):format(n, d.friction, seconds)
end

print(("\nGeometric factor of safety (thickness over minimum thickness), %d voussoirs, no sliding"):format(VOUSSOIRS))
print(("%6s %12s %8s %10s"):format("t/R", "minimum t/R", "factor", "seconds"))
for _, ratio in ipairs{ 0.12, 0.15, 0.2, 0.3 } do
  local g = ashlar.geometric_factor(function(t) return arch(t) end, ratio, { friction = math.huge, tolerance = 1e-8 })
  print(("%6.2f %12.8f %8.4f %10.4f"):format(ratio, g.minimum, g.factor, g.seconds))
  csv[#csv + 1] = ("geometric_factor,%g,%d,%.12g,,%.6f"):format(ratio, VOUSSOIRS, g.factor, g.seconds)
end
script_support.write_atomically(output .. "/stability_margins.csv", table.concat(csv, "\n") .. "\n")
print("wrote " .. output .. "/stability_margins.csv")
