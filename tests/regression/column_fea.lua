-- Elastic FEA of a column on fixed ground against the closed forms of a bar:
-- under its own weight the top settles rho g L^2 / (2 E), under an axial
-- load P on top by P L / (E A). With Poisson's ratio 0 the fixed base does
-- not restrain any lateral strain, so the 3D bar is the 1D one, whose
-- linear elements with consistent loads are exact at the nodes.
local ashlar = require "ashlar"
local check = require "ashlar.regression"

local L, width, E, rho, g = 2, 0.5, 20e9, 2400, 9.81

local function column()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { width, width, L }, center = { 0, 0, L / 2 }, density = rho }, { name = "column" })
  s:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "ground" })
  return s
end

-- The mean vertical displacement of the nodes on the top face.
local function top_settlement(fe)
  local sum, count = 0, 0
  for n, p in ipairs(fe.nodes) do
    if math.abs(p[3] - L) < 1e-9 then sum, count = sum + fe.displacements[n][3], count + 1 end
  end
  return -sum / count
end

local self_weight = ashlar.fea(column(), { young = E, poisson = 0, refine = 4 })
check("self-weight: status", self_weight.status, { reference = "compression_only" })
check("self-weight: top settlement (m)", top_settlement(self_weight),
      { reference = rho * g * L ^ 2 / (2 * E), reference_tolerance = 1e-9 })

-- One element: a load at the top face's centre is shared equally by its
-- four corners, so the top stays flat.
local P = 1e6
local loaded = column()
loaded:add_load{ block = 1, force = { 0, 0, -P }, at = { 0, 0, L } }
local axial = ashlar.fea(loaded, { young = E, poisson = 0, refine = 1 })
check("self-weight and 1 MN on top: top settlement (m)", top_settlement(axial),
      { reference = rho * g * L ^ 2 / (2 * E) + P * L / (E * width ^ 2), reference_tolerance = 1e-9 })
