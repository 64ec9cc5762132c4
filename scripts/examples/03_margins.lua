-- Tutorial 03: margins: load factor, friction demand, geometric factor,
-- tilt (docs/guide/03_margins.md).
-- usage: ashlar scripts/examples/03_margins.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

local function arch(t) return models.arch{ radius = 1, thickness = t, voussoirs = 64 } end

-- Load factor: the largest horizontal acceleration (in g) it carries.
local f = ashlar.load_factor(arch(0.15), { friction = math.huge })
print(string.format("load factor %.7f (%s)", f.factor, f.status))
local hinges = {}
for _, l in ipairs(f.limit) do hinges[#hinges + 1] = string.format("%d-%d %s", l.a, l.b, l.mode) end
print("limit joints: " .. table.concat(hinges, ", "))

-- Friction demand: the least friction coefficient with which it stands.
local d = ashlar.friction_demand(arch(0.12))
print(string.format("friction demand at t/R 0.12: %.4f", d.friction))

-- Geometric factor: as-built thickness over the least that stands.
local g = ashlar.geometric_factor(arch, 0.15, { friction = math.huge })
print(string.format("minimum t/R %.5f, geometric factor %.3f", g.minimum, g.factor))

-- Tilt: the tilt-table test of the same lateral load.
local tilted = ashlar.tilt(arch(0.15), math.atan(0.1))
print("tilted by atan 0.1: stable", ashlar.analyze(tilted, { friction = math.huge }).stable)

-- Load factor against thickness.
local rows = {}
for k = 0, 8 do
  local t = 0.11 + 0.025 * k
  rows[#rows + 1] = { t = t, factor = ashlar.load_factor(arch(t), { friction = math.huge }).factor }
end
ashlar.chart{ path = out .. "/03_load_factor.svg", data = rows, x = "t", y = "factor",
              title = "Semicircular arch, 64 voussoirs, no sliding", x_label = "t / R",
              y_label = "load factor (g)" }

assert(f.status == "optimal" and math.abs(f.factor - 0.1446973) < 1e-6, "load factor of t/R 0.15")
assert(#f.limit == 4, "four hinges")
assert(math.abs(d.friction - 0.3817) < 1e-4, "friction demand of t/R 0.12")
assert(math.abs(g.minimum - 0.1073832) < 1e-6 and math.abs(g.factor - 1.3969) < 1e-3, "geometric factor")
