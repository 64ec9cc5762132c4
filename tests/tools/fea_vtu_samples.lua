-- Writes the FEA results that tests/tools/check_fea_vtu.py reads back with
-- its own VTU reader (vtu_reader.py):
--   ashlar fea_vtu_samples.lua <folder>
-- Each case is exported twice, <case>_binary.vtu (the default format) and
-- <case>_ascii.vtu; <folder>/cases.json says what each case is made of, as
-- the scripts built it, for the checks' references.
--   column   a 0.5 x 0.5 x 2 m column (refine 4, Poisson's ratio 0, with
--            stresses) on a pentagonal slab: a support that is not a
--            hexahedron, so it is written as a VTK_POLYHEDRON
--   arch     the 5-voussoir default arch (refine 2, with stresses) on its
--            two box supports (VTK_HEXAHEDRON cells)
--   plain    the same arch without stresses
local ashlar = require "ashlar"
local models = require "ashlar.models"

local folder = arg[1]
assert(folder, "usage: ashlar fea_vtu_samples.lua <folder>")

local L, width, rho = 2, 0.5, 2400

local function column()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { width, width, L }, center = { 0, 0, L / 2 }, density = rho }, { name = "column" })
  local pentagon = {}
  for k = 0, 4 do
    local a = 2 * math.pi * k / 5
    pentagon[#pentagon + 1] = { math.cos(a), math.sin(a), 0 }
  end
  s:add(ashlar.prism(pentagon, { 0, 0, -0.2 }), { support = true, name = "ground" })
  return s
end

local cases = {
  { name = "column", structure = column(), refine = 4, options = { poisson = 0, stresses = true } },
  { name = "arch", structure = models.arch{ voussoirs = 5 }, refine = 2, options = { stresses = true } },
  { name = "plain", structure = models.arch{ voussoirs = 5 }, refine = 2, options = {} },
}

local description = {}
for _, case in ipairs(cases) do
  local options = { refine = case.refine }
  for k, v in pairs(case.options) do options[k] = v end
  local fe = ashlar.fea(case.structure, options)
  fe:export(folder .. "/" .. case.name .. "_binary.vtu")
  fe:export(folder .. "/" .. case.name .. "_ascii.vtu", { format = "ascii" })
  local blocks = {}
  for i = 1, #case.structure do
    blocks[i] = ('{"support": %s, "vertices": %d}'):format(tostring(case.structure:is_support(i)),
                                                          #case.structure:block(i):vertices())
  end
  description[#description + 1] = ('"%s": {"refine": %d, "stresses": %s, "blocks": [%s]}')
    :format(case.name, case.refine, tostring(case.options.stresses == true), table.concat(blocks, ", "))
end
local out = assert(io.open(folder .. "/cases.json", "w"))
out:write("{", table.concat(description, ",\n "), ",\n \"column_height\": ", L, ", \"density\": ", rho, "}\n")
out:close()
