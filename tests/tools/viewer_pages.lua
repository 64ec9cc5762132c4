-- Writes the pages the browser tests open (tests/tools/check_viewer.js runs it):
--   ashlar viewer_pages.lua <case> <folder>
-- arch: a 9-voussoir arch, planar, with its forces, thrust line and
-- interfaces;
-- dome: a small dome coloured by the height of each block (coolwarm), with
-- a legend (from 0: no value is negative);
-- animation: a red block dropped onto the ground, where it comes to rest
-- (sim:export's page, with its player).
local ashlar = require "ashlar"
local models = require "ashlar.models"

local case, folder = arg[1], arg[2]
assert(case and folder, "usage: ashlar viewer_pages.lua arch|dome|animation <folder>")

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
else
  error("unknown case " .. tostring(case))
end
