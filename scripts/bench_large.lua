-- One large equilibrium analysis, for timing the whole process from outside:
--   /usr/bin/time -v build/bin/ashlar scripts/bench_large.lua KIND
-- KIND:
--   planar     running-bond wall of 100 x 100 bricks (10,051 blocks), planar solve
--   wall       the same wall solved as a general 3D problem
--   vault      barrel vault, 50 voussoirs x 200 courses (10,027 blocks)
--   vault100k  barrel vault, 100 voussoirs x 1000 courses (100,052 blocks)
-- friction 0.7. Prints iterations, factorisations, the objective (to compare
-- answers between builds), the time split and peak memory. The 10k models
-- find their contacts first through s:interfaces() (timed apart, its Lua
-- tables count in the peak); vault100k leaves contact detection to the
-- analysis, so that its peak is the engine's.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local BUILDERS = {
  planar = function() return models.wall{ length = 100 * 0.24, height = 100 * 0.07 } end,
  wall = function()
    local s = models.wall{ length = 100 * 0.24, height = 100 * 0.07 }
    s:set_planar(false)
    return s
  end,
  vault = function()
    return models.barrel_vault{ radius = 2, thickness = 0.4, voussoirs = 50, courses = 200, length = 50,
                                bond = "running" }
  end,
  vault100k = function()
    return models.barrel_vault{ radius = 2, thickness = 0.4, voussoirs = 100, courses = 1000, length = 250,
                                bond = "running" }
  end,
}

local kind = arg[1]
local build = BUILDERS[kind]
if not build then
  io.stderr:write("usage: ashlar scripts/bench_large.lua planar|wall|vault|vault100k\n")
  os.exit(1)
end
local s = build()
local contacts = ""
if kind ~= "vault100k" then
  local t0 = ashlar.clock()
  s:interfaces()
  contacts = (" contacts %.2f s"):format(ashlar.clock() - t0)
end
collectgarbage()
local before = ashlar.memory()
local r = ashlar.analyze(s, { friction = 0.7 })
local t = r.timings
print(("%s: %d blocks%s; %s, stable %s, %d iterations, %d factorisations, objective %.12g"):format(kind, #s,
  contacts, r.status, tostring(r.stable), r.iterations, r.factorizations, r.objective))
print(("  setup %.2f s, assembly %.2f s, factorisation %.2f s, solve %.2f s, analysis %.2f s"):format(t.setup,
  t.assembly, t.factorization, t.solve, r.seconds))
print(("  resident before the analysis %.0f MiB, peak %.0f MiB"):format(before.resident_mb, ashlar.memory().peak_mb))
