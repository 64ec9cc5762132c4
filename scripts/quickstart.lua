-- ashlar quickstart: builds a small scene, finds its contact interfaces,
-- analyses the equilibrium of an arch, exports both as glTF (the arch also
-- as the interactive HTML viewer) and prints a summary.
--   ashlar scripts/quickstart.lua [output folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"

local out = arg and arg[1] or "."

-- A running-bond garden wall, and beside it a leaning stack of three stones.
local s = models.wall{ length = 2.4, height = 0.84, thickness = 0.11, brick = { 0.24, 0.07 } }
s:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 2, -0.1 } }, { support = true, name = "plinth" })
for i = 1, 3 do
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.1 * i, 2, 0.25 + 0.5 * (i - 1) } },
        { name = "stone " .. i })
end

local start = ashlar.clock()
local interfaces = s:interfaces()
local seconds = ashlar.clock() - start

local supports, mass, area = 0, 0, 0
local heights = {}
for i = 1, #s do
  local b = s:block(i)
  if s:is_support(i) then supports = supports + 1 else mass = mass + b:mass() end
  heights[i] = b:centroid()[3]
end
for _, f in ipairs(interfaces) do area = area + f.area end

local glb = out .. "/quickstart.glb"
ashlar.export(s, glb, { color = { values = heights, map = "viridis" }, interfaces = true })
s:save(out .. "/quickstart.json")

print(("ashlar %s quickstart"):format(ashlar.version))
print(("  blocks       %6d (%d supports)"):format(#s, supports))
print(("  free mass    %10.1f kg"):format(mass))
print(("  interfaces   %6d, total contact area %.4f m^2, found in %.2f ms"):format(#interfaces, area, seconds * 1e3))
local f = interfaces[#interfaces]
print(("  last contact: blocks %d-%d ('%s' on '%s'), area %.3f m^2, %d vertices"):format(
  f.a, f.b, s:name(f.b), s:name(f.a), f.area, #f.vertices))
print(("  wrote %s and %s/quickstart.json"):format(glb, out))

-- A semicircular arch of 31 voussoirs: does it stand, and how thin could it be?
local arch = models.arch{ radius = 5, thickness = 0.6, voussoirs = 31, depth = 1 }
local r = ashlar.analyze(arch, { friction = 0.7 })
local thrust = r:thrust_line()
print(("  arch: %d voussoirs, t/R = %.3f: %s (infeasibility %g, %s in %d iterations, %.1f ms)"):format(
  #arch - 2, 0.6 / 5, r.stable and "stands" or "falls", r.infeasibility, r.status, r.iterations, r.seconds * 1e3))
print(("        thrust line through %d joints, at z = %.3f m beside the keystone"):format(#thrust, thrust[(#thrust + 1) // 2][3]))
local thin, thick = 0.09, 0.12
while thick - thin > 1e-4 do
  local ratio = (thin + thick) / 2
  local stands = ashlar.analyze(models.arch{ radius = 5, thickness = ratio * 5, voussoirs = 31 },
                                { friction = math.huge }).stable
  if stands then thick = ratio else thin = ratio end
end
print(("        minimum thickness without sliding: t/R = %.4f (limit for many voussoirs: 0.1075)"):format(thick))
ashlar.export(arch, out .. "/arch.glb", { result = r, forces = true, thrust = true })
ashlar.export(arch, out .. "/arch.html", { result = r, forces = true, thrust = true, interfaces = true })
print(("  wrote %s/arch.glb with force arrows and the thrust line, and %s/arch.html to open in a browser"):format(out, out))
