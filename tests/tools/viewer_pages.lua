-- Writes the pages the browser tests open (tests/tools/check_viewer.js runs it):
--   ashlar viewer_pages.lua <case> <folder>
-- arch: a 9-voussoir arch, planar, with its forces, thrust line and
-- interfaces;
-- dome: a small dome coloured by the height of each block (coolwarm), with
-- a legend (from 0: no value is negative);
-- animation: a red block dropped onto the ground, where it comes to rest
-- (sim:export's page, with its player);
-- mechanism: a 16-voussoir arch (R 1 m, t 0.15 m, planar) at its load
-- factor, the mechanism played to 0.2 m, paused, its fastest block red
-- (opaque);
-- mechanism.json says which block that is and where the mechanism moves
-- its centroid (from the load factor's own result, in Lua);
-- network: a small dome with its thrust network and the forces at each
-- contact vertex (normal and friction parts).
local ashlar = require "ashlar"
local models = require "ashlar.models"

local case, folder = arg[1], arg[2]
assert(case and folder, "usage: ashlar viewer_pages.lua arch|dome|animation|mechanism|network <folder>")

if case == "arch" then
  local s = models.arch{ voussoirs = 9 }
  s:set_planar(true)
  local r = ashlar.analyze(s, { friction = 0.7 })
  assert(r.stable, "the test arch should stand")
  ashlar.export(s, folder .. "/arch.html",
                { result = r, forces = true, thrust = true, interfaces = true, title = "test arch" })
elseif case == "dome" then
  local s = models.dome{ meridians = 8, parallels = 4 }
  local heights = {}
  -- Above the supports' underside (z = -0.5 m): every value positive.
  for i = 1, #s do heights[i] = s:block(i):centroid()[3] + 0.5 end
  ashlar.export(s, folder .. "/dome.html",
                { color = { values = heights, map = "coolwarm" }, legend = "height (m)" })
elseif case == "animation" then
  local s = ashlar.structure()
  s:add(ashlar.box{ size = {3, 2, 0.3}, center = {0, 0, -0.15} }, { support = true })
  s:add(ashlar.box{ size = {0.6, 0.6, 0.6}, center = {0, 0, 1.3} })
  local sim = ashlar.simulate(s, { duration = 0.8 })
  assert(sim.moved and sim.max_displacement > 0.9, "the test block should fall 1 m")
  sim:export(folder .. "/animation.html",
             { fps = 30, color = { {0.7, 0.7, 0.7}, {0.9, 0.1, 0.1} }, title = "test drop" })
elseif case == "mechanism" then
  local s = models.arch{ radius = 1, thickness = 0.15, voussoirs = 16 }
  s:set_planar(true)
  local f = ashlar.load_factor(s, { friction = math.huge })
  assert(f.status == "optimal" and #f.limit == 4, "the test arch should have a four-hinge mechanism")
  local fastest, speed = nil, 0
  for i = 1, #s do
    local v = f.mechanism[i].velocity
    local size = math.sqrt(v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2)
    if size > speed then fastest, speed = i, size end
  end
  local colors = {}
  for i = 1, #s do colors[i] = i == fastest and { 0.9, 0.1, 0.1 } or { 0.75, 0.75, 0.75 } end
  ashlar.export(s, folder .. "/mechanism.html",
                { result = f, mechanism = 0.2, autoplay = false, color = colors, opacity = 1, title = "test mechanism" })
  local v, lo, hi = f.mechanism[fastest].velocity, s:bounds()
  local file = assert(io.open(folder .. "/mechanism.json", "w"))
  file:write(('{"block": %d, "shift": [%.17g, %.17g], "width": %.17g, "reach": 0.2}\n')
             :format(fastest, 0.2 * v[1], 0.2 * v[3], hi[1] - lo[1]))
  file:close()
elseif case == "network" then
  local s = models.dome{ meridians = 8, parallels = 4 }
  local r = ashlar.analyze(s, { friction = 0.7 })
  assert(r.stable, "the test dome should stand")
  ashlar.export(s, folder .. "/network.html", { result = r, thrust = true, forces = "vertices", title = "test network" })
else
  error("unknown case " .. tostring(case))
end
