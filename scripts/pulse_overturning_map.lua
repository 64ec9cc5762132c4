-- The overturning map of a slender block (0.1 m wide, 1 m tall, 0.2 m deep:
-- alpha = 0.0997 rad, p = 3.83 rad/s) under one-sine pulses of ground
-- acceleration a_p sin(w_p t), over w_p / p x a_p / (g tan alpha): each cell an
-- ashlar.simulate run (collapsed by sim:summary()'s criterion), drawn by
-- st:chart{ kind = "map" } with its boundary, and the closed form of Zhang and
-- Makris (2001, J. Eng. Mech. 127(5); scripts/rocking_pulse.lua) dashed over
-- it: every amplitude where its verdict changes.
--   build/bin/ashlar scripts/pulse_overturning_map.lua [output folder, default "docs/figures/dynamics"]
-- Writes pulse_overturning_map.png. Prints the runs' time, and per
-- frequency the simulated minimum overturning amplitude (the lowest
-- collapsed cell, and the highest standing cell below it) next to the closed
-- form's.
local ashlar = require "ashlar"
local support = require "script_support"
package.path = arg[0]:gsub("[^/]*$", "") .. "?.lua;" .. package.path
local rocking = require "rocking_pulse"

local folder = arg[1] or "docs/figures/dynamics"
support.make_folders(folder)

local width, height, depth = 0.1, 1.0, 0.2
local block = rocking.block(width, height)
local ratios, amplitudes = ashlar.range(1.5, 8, 14), ashlar.range(0.8, 6, 27)

local study
support.timed(("%d x %d simulations"):format(#ratios, #amplitudes), function()
  study = ashlar.study{
    name = "pulse_overturning", workers = 1, progress = false,
    params = { ratio = ratios, amplitude = amplitudes },
    run = function(p)
      local collapsed, peak = rocking.simulate(width, height, depth, p.amplitude * block.threshold, p.ratio * block.p)
      return { collapsed = collapsed, peak = peak }
    end,
  }
end)

-- The closed form's transitions on a fine line of frequencies: each the
-- amplitude where its verdict changes; the j-th transitions of neighbouring
-- frequencies join into one curve, which ends where that transition ends.
local drawn, current = {}, {}
for k = 0, 65 do
  local ratio = ratios[1] + (ratios[#ratios] - ratios[1]) * k / 65
  local changes = rocking.transitions(block, ratio * block.p, block.threshold, 6.2 * block.threshold, 160)
  for j = 1, math.max(#changes, #current) do
    if not changes[j] then
      current[j] = nil
    else
      if not current[j] then
        current[j] = {}
        drawn[#drawn + 1] = current[j]
      end
      table.insert(current[j], { ratio, changes[j].amplitude / block.threshold })
    end
  end
end
for j = #drawn, 1, -1 do
  if #drawn[j] < 2 then table.remove(drawn, j) end
end

study:chart{ path = folder .. "/pulse_overturning_map.png", x = "ratio", y = "amplitude", z = "collapsed",
             kind = "map", curves = drawn, width = 1000, height = 700,
             x_label = "ω_p / p", y_label = "a_p / (g tan α)", z_label = "overturned",
             title = "Block 0.1 × 1 m under a one-sine pulse: simulated (cells), Zhang & Makris 2001 (dashed)" }

-- Per frequency: the simulated bracket of the minimum overturning amplitude.
local by_ratio = {}
for _, row in ipairs(study:rows()) do
  by_ratio[row.ratio] = by_ratio[row.ratio] or {}
  table.insert(by_ratio[row.ratio], row)
end
print("w_p/p   simulated minimum in (a_p/(g tan alpha))   closed form")
for _, ratio in ipairs(ratios) do
  local rows = by_ratio[ratio]
  table.sort(rows, function(a, b) return a.amplitude < b.amplitude end)
  local below, first
  for _, row in ipairs(rows) do
    if row.collapsed then first = row.amplitude break end
    below = row.amplitude
  end
  local change = rocking.transitions(block, ratio * block.p, block.threshold, 6.2 * block.threshold, 160)[1]
  print(("%5.2f   (%s, %s]   %s"):format(ratio, tostring(below), tostring(first),
        change and ("%.4f"):format(change.amplitude / block.threshold) or "none below 6.2"))
end
