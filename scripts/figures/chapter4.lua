-- The thesis's chapter 4 pictures (Shin 2014, figures 4-10), remade:
--   ashlar scripts/figures/chapter4.lua [folder]     (default docs/figures/chapter4)
-- Writes per figure a coloured .glb, a legend (.png) for its colour map,
-- and, when f3d and xvfb-run are installed (Debian: f3d xvfb), a PNG
-- rendering; figure 7 is an elevation drawing (.svg and .png). Prints the
-- numbers each picture shows and the time of each analysis.
local ashlar = require "ashlar"
local models = require "ashlar.models"
-- script_support.lua lives in scripts/, one folder up.
package.path = (arg[0]:match("^(.*)/[^/]+/[^/]+$") or "..") .. "/?.lua;" .. package.path
local support = require "script_support"

local folder = arg[1] or "docs/figures/chapter4"
support.make_folders(folder)
local NO_SLIDING = { friction = math.huge }

local pictures = support.can_render()
if not pictures then print("f3d or xvfb-run not found: only .glb files and legends are written") end

-- f3d's camera, turned from the front (the x-z plane seen from -y).
local FRONT = { azimuth = 0, elevation = 0 }
local ABOVE = { azimuth = 0, elevation = 25 }

local function render(glb, view)
  if pictures then support.render(glb, view) end
end

-- Exports s coloured by values[i] (supports grey: their value is the
-- range's low end) with a legend; values above `cap` show as `cap`.
local function coloured(s, name, values, label, view, options)
  options = options or {}
  local lo, hi = math.huge, -math.huge
  local shown = {}
  for i = 1, #s do
    if not s:is_support(i) then
      shown[i] = math.min(values[i], options.cap or math.huge)
      lo, hi = math.min(lo, shown[i]), math.max(hi, shown[i])
    end
  end
  if options.range then lo, hi = options.range[1], options.range[2] end
  if hi <= lo then hi = lo + 1 end
  for i = 1, #s do shown[i] = shown[i] or lo end
  local map = options.map or "viridis"
  local glb = ("%s/%s.glb"):format(folder, name)
  ashlar.export(s, glb, { color = { values = shown, map = map, range = { lo, hi } }, traces = options.traces })
  ashlar.legend(("%s/%s_legend.png"):format(folder, name), { map = map, range = { lo, hi }, label = label })
  render(glb, view)
end

local timed = support.timed

-- Figure 4: a dome, the force change for a bottom block's and a middle block's weight.
print("figure 4: weight sensitivity, dome 16 x 12")
local dome = models.dome{ meridians = 16, parallels = 12 }
-- The meridian that faces the camera (ashlar's -y side).
local facing, lowest_y = 1, math.huge
for b = 1, 16 do
  local y = dome:block(dome:find("course 1 block " .. b)):centroid()[2]
  if y < lowest_y then facing, lowest_y = b, y end
end
for _, case in ipairs{ { "bottom", "course 1 block " .. facing }, { "middle", "course 6 block " .. facing } } do
  local ws = timed("weight_sensitivity " .. case[1], function() return ashlar.weight_sensitivity(dome, case[2]) end)
  local i = dome:find(case[2])
  local others, largest = 0, 0
  for j = 1, #dome do
    if j ~= i and not dome:is_support(j) then others = others + ws[j]; largest = math.max(largest, ws[j]) end
  end
  print(("    own %.3f N/N, others' largest %.3f, sum %.3f"):format(ws[i], largest, others))
  coloured(dome, "figure4_dome_" .. case[1], ws, "force change (N per N of weight)", ABOVE)
end

-- Figure 5: the largest multiple of its weight each voussoir of an arch can carry.
print("figure 5: load capacity, arch of 31 voussoirs, no sliding")
local arch = models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 }
local cap = timed("load_capacity", function() return ashlar.load_capacity(arch, NO_SLIDING) end)
local maxima = {}
for i = 1, #arch do maxima[i] = cap[i] and cap[i].max or 0 end
print(("    crown %.3f, neighbours %.3f / %.3f, by the supports %s"):format(maxima[16], maxima[15], maxima[17], maxima[1]))
coloured(arch, "figure5_arch_capacity", maxima, "largest multiple of own weight (capped at 10)", FRONT,
         { cap = 10 })

-- Figure 6: the least multiple of its weight each block of a vault on
-- flying buttresses needs, the buttresses whole, in 2 and in 4.
print("figure 6: minimum weights, vault on flying buttresses")
for _, buttress_blocks in ipairs{ 1, 2, 4 } do
  local s = models.buttressed_vault{ buttress_blocks = buttress_blocks }
  local c = timed("load_capacity, buttress in " .. buttress_blocks,
                  function() return ashlar.load_capacity(s, { tolerance = 1e-7 }) end)
  local minima, needing = {}, {}
  for i = 1, #s do
    minima[i] = c[i] and c[i].min or 0
    if minima[i] > 1e-6 then needing[#needing + 1] = ("%s %.3f"):format(s:name(i), minima[i]) end
  end
  print("    needing weight: " .. (#needing > 0 and table.concat(needing, ", ") or "none"))
  -- One range for the three pictures, so that they compare.
  coloured(s, ("figure6_vault_buttress%d"):format(buttress_blocks), minima, "least multiple of own weight", FRONT,
           { range = { 0, 0.35 } })
end

-- Figure 7: thrust lines of a flying buttress without and with its pinnacle.
print("figure 7: thrust lines, flying buttress")
for _, height in ipairs{ 0, 4 } do
  local s = models.flying_buttress{ pinnacle_height = height }
  local r = ashlar.analyze(s, { tolerance = 1e-7 })
  for _, extension in ipairs{ "svg", "png" } do
    ashlar.draw(s, ("%s/figure7_buttress_pinnacle%d.%s"):format(folder, height, extension),
                { result = r, title = ("flying buttress, pinnacle %g m: %s"):format(height, r.stable and "stands" or "falls") })
  end
  print(("    pinnacle %g m: %s"):format(height, r.stable and "stands" or "falls"))
end

-- Figure 8: three stacked blocks, only the middle one weighted.
print("figure 8: necessary weights, three stacked blocks")
local stack = ashlar.structure()
stack:add(ashlar.box{ size = { 4, 2, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "ground" })
stack:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.25 } }, { name = "bottom" })
stack:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.6, 0, 0.75 } }, { name = "middle" })
stack:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.2, 0, 1.25 } }, { name = "top" })
local needed = timed("necessary_weights", function() return ashlar.necessary_weights(stack, "middle") end)
local own = stack:block(3):mass() * 9.81
print(("    top %.3f, bottom %.2g x the middle's weight"):format(needed[4] / own, needed[2] / own))
local shares = {}
for i = 1, #stack do shares[i] = needed[i] / own end
coloured(stack, "figure8_stack", shares, "necessary weight / middle block's weight", FRONT)

-- Figure 9: important weights of an arch and a dome.
print("figure 9: important weights")
local arch_weights = timed("important_weights, arch", function() return ashlar.important_weights(arch, NO_SLIDING) end)
coloured(arch, "figure9_arch", arch_weights, "sum of necessary weights / volume (N/m^3)", FRONT)
local dome_weights = timed("important_weights, dome 16 x 12", function() return ashlar.important_weights(dome) end)
coloured(dome, "figure9_dome", dome_weights, "sum of necessary weights / volume (N/m^3)", ABOVE)

-- Figure 10: load traces of an H frame's beam and of an asymmetric frame's top block.
print("figure 10: load traces")
local frame = models.h_frame{}
local flow = timed("trace_loads, H frame", function() return ashlar.trace_loads(frame, "beam", { traces = 200 }) end)
for _, arrived in ipairs(flow.shares) do
  print(("    %s: %.3f"):format(frame:name(frame:is_support(arrived.a) and arrived.b or arrived.a), arrived.share))
end
local random = ashlar.trace_loads(frame, "beam", { traces = 200, start = "random" })
-- The PNG shows the traced block and the ground only (f3d draws blocks
-- opaque, which would hide the traces); the .glb has every block, translucent.
for _, case in ipairs{ { "figure10_h_frame", flow }, { "figure10_h_frame_random", random } } do
  ashlar.export(frame, ("%s/%s.glb"):format(folder, case[1]), { traces = case[2] })
  local shown = ashlar.structure()
  for i = 1, #frame do
    if frame:is_support(i) or frame:name(i) == "beam" then shown:add(frame:block(i), { support = frame:is_support(i) }) end
  end
  local glb = ("%s/%s_traces.glb"):format(folder, case[1])
  ashlar.export(shown, glb, { traces = case[2] })
  render(glb, FRONT)
end
