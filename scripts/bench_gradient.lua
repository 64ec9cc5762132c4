-- The cost of one structural gradient against the analysis it differentiates
-- (target: under 20%), on models of growing size.
--   ashlar scripts/bench_gradient.lua [output folder, default "docs/figures"]
-- Prints and writes bench_gradient.csv: blocks, analysis and gradient seconds
-- (the best of 3 runs each) and their ratio.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"

local folder = arg[1] or "docs/figures"
local cases = {
  { "arch 64 voussoirs", function() return models.arch{ radius = 5, thickness = 0.3, voussoirs = 64 } end, { friction = math.huge } },
  { "arch 1024 voussoirs", function() return models.arch{ radius = 5, thickness = 0.3, voussoirs = 1024 } end, { friction = math.huge } },
  { "dome 24 x 12", function() return models.dome{ radius = 5, thickness = 0.15, meridians = 24, parallels = 12 } end, { friction = math.huge } },
  { "dome 64 x 32", function() return models.dome{ radius = 5, thickness = 0.15, meridians = 64, parallels = 32 } end, { friction = math.huge } },
  { "wall 20 x 40 stack bond, pushed", function()
      local s = models.wall{ length = 4.8, height = 2.8, bond = "stack" }
      s:add_load{ block = #s, force = { 3e3, 0, 0 } }
      return s end, { friction = 0.6 } },
}
local rows = { "model,blocks,analysis_s,gradient_s,ratio" }
print(("%-34s %7s %11s %11s %7s"):format("model", "blocks", "analysis s", "gradient s", "ratio"))
for _, case in ipairs(cases) do
  local s = case[2]()
  local analysis, gradient = math.huge, math.huge
  for _ = 1, 3 do
    local g = ashlar.gradient(s, case[3])
    analysis = math.min(analysis, g.analysis_seconds)
    gradient = math.min(gradient, g.seconds)
  end
  print(("%-34s %7d %11.4f %11.4f %6.1f%%"):format(case[1], #s, analysis, gradient, 100 * gradient / analysis))
  rows[#rows + 1] = ("%s,%d,%.6f,%.6f,%.4f"):format(case[1], #s, analysis, gradient, gradient / analysis)
end
script_support.write_atomically(folder .. "/bench_gradient.csv", table.concat(rows, "\n") .. "\n")
