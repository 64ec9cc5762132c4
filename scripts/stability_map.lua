-- The stability map of a semicircular arch of 16 voussoirs (R = 1) over
-- thickness t/R × friction coefficient μ, drawn by ashlar.chart{ kind = "map" }
-- with the boundary between the stable and unstable cells.
--   build/bin/ashlar scripts/stability_map.lua [output folder, default "docs/figures/charts"]
-- Writes stability_map.png and stability_map.svg. Prints the time the
-- analyses took and where the boundary crosses the largest μ and the
-- largest t, next to the margins it should meet there: the minimum
-- thickness without sliding (ashlar.geometric_factor) and the friction
-- demand (ashlar.friction_demand).
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local folder = arg[1] or "docs/figures/charts"
support.make_folders(folder)

local function arch(t)
  return models.arch{ radius = 1, thickness = t, voussoirs = 16 }
end

local ts, mus = ashlar.range(0.09, 0.13, 41), ashlar.range(0.2, 0.6, 41)
local rows = {}
support.timed(("%d x %d analyses"):format(#ts, #mus), function()
  for _, t in ipairs(ts) do
    for _, mu in ipairs(mus) do
      rows[#rows + 1] = { t = t, mu = mu, stable = ashlar.analyze(arch(t), { friction = mu }).stable }
    end
  end
end)

local map
for _, extension in ipairs{ "png", "svg" } do
  map = ashlar.chart{ path = folder .. "/stability_map." .. extension, data = rows, x = "t", y = "mu",
                      z = "stable", kind = "map", width = 1000, height = 700, x_label = "t / R",
                      y_label = "friction coefficient μ",
                      title = "Semicircular arch, 16 voussoirs: stable (blue) and unstable (vermillion)" }
end

-- Where the boundary crosses coordinate `axis` (1: t, 2: μ) = value, along
-- its segments parallel to the other axis.
local function crossing(axis, value)
  local other = 3 - axis
  for _, line in ipairs(map.boundary) do
    for k = 2, #line do
      local a, b = line[k - 1], line[k]
      if math.min(a[axis], b[axis]) < value and value < math.max(a[axis], b[axis]) and a[other] == b[other] then
        return a[other]
      end
    end
  end
end

local g = ashlar.geometric_factor(arch, ts[#ts], { friction = math.huge })
local d = ashlar.friction_demand(arch(ts[#ts]), { progress = false })
print(("at mu = %.2f the boundary is at t/R = %.4f; minimum thickness (no sliding) %.5f"):format(
  mus[#mus], crossing(2, mus[#mus]), g.minimum))
print(("at t/R = %.3f the boundary is at mu = %.3f; friction demand %.4f"):format(
  ts[#ts], crossing(1, ts[#ts]), d.friction))
