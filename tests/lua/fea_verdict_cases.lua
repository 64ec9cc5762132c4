-- The model library's FEA verdicts against the equilibrium method's: every
-- model the FEA can mesh (free blocks that are hexahedra, no cables), at
-- its defaults and at a thin or overhanging variant. The FEA's contact has
-- unlimited friction, so its verdict is compared with equilibrium at
-- friction = math.huge; the default friction's verdict is listed to show
-- where friction decides. Used by tests/lua/fea_verdicts_spec.lua and
-- scripts/fea_verdicts.lua (which writes the table in docs/verification.md).
local ashlar = require "ashlar"
local models = require "ashlar.models"

local M = {}

M.cases = {
  { "arch t/R 0.12", function() return models.arch{ radius = 5, thickness = 0.6, voussoirs = 24 } end },
  { "arch t/R 0.10", function() return models.arch{ radius = 5, thickness = 0.5, voussoirs = 24 } end },
  { "barrel_vault", function() return models.barrel_vault{} end },
  { "barrel_vault thickness 0.25", function() return models.barrel_vault{ thickness = 0.25 } end },
  { "buttressed_vault", function() return models.buttressed_vault{} end },
  { "buttressed_vault pier_width 0.8", function() return models.buttressed_vault{ pier_width = 0.8 } end },
  { "buttressed_vault pier_width 0.65", function() return models.buttressed_vault{ pier_width = 0.65 } end },
  { "column", function() return models.column{} end },
  { "column width 0.1", function() return models.column{ width = 0.1, depth = 0.1 } end },
  { "dome oculus 0.25", function() return models.dome{ oculus = 0.25 } end },
  { "dome oculus 0.25 thickness 0.1", function() return models.dome{ oculus = 0.25, thickness = 0.1 } end },
  { "flying_buttress", function() return models.flying_buttress{} end },
  { "flying_buttress pinnacle_height 0", function() return models.flying_buttress{ pinnacle_height = 0 } end },
  { "flying_buttress pier_width 0.9", function() return models.flying_buttress{ pier_width = 0.9 } end },
  { "groin_vault", function() return models.groin_vault{} end },
  { "groin_vault thickness 0.15", function() return models.groin_vault{ thickness = 0.15 } end },
  { "h_frame", function() return models.h_frame{} end },
  { "h_frame width 0.15", function() return models.h_frame{ width = 0.15 } end },
  { "post_and_lintel", function() return models.post_and_lintel{} end },
  { "stack", function() return models.stack{} end },
  { "stack offset 0.3", function() return models.stack{ offset = 0.3 } end },
  { "wall", function() return models.wall{} end },
  { "wall thickness 0.05", function() return models.wall{ thickness = 0.05 } end },
}

local function verdict(stable) return stable and "stands" or "falls" end
local FEA_VERDICT = { compression_only = "stands", mechanism = "falls" }

-- One row: the verdicts (FEA ones are its status where it gives none).
function M.row(case)
  local s = case[2]()
  local fea = ashlar.fea(s)
  local relaxation = ashlar.fea(s, { method = "relaxation", max_relax_iterations = 20 })
  return {
    name = case[1],
    blocks = #s,
    unlimited_friction = verdict(ashlar.analyze(s, { friction = math.huge }).stable),
    default_friction = verdict(ashlar.analyze(s).stable),
    fea = FEA_VERDICT[fea.status] or fea.status,
    fea_solves = fea.iterations + 1,
    fea_interior_point = fea.interior_point_iterations,
    relaxation = FEA_VERDICT[relaxation.status] or relaxation.status,
  }
end

-- The table in docs/verification.md: a header, then one line per row.
M.header = {
  "| model | blocks | equilibrium, μ = ∞ | equilibrium, μ = 0.7 | FEA, unilateral (solves, IPOPT iterations) | FEA, relaxation (thesis, 20 releases) |",
  "|---|---|---|---|---|---|",
}

function M.table_line(row)
  return string.format("| %s | %d | %s | %s | %s (%d, %d) | %s |", row.name, row.blocks, row.unlimited_friction,
                       row.default_friction, row.fea, row.fea_solves, row.fea_interior_point, row.relaxation)
end

-- The verdict columns of a table line (its name, then the four verdicts),
-- without the counts, which round-off on another machine may change.
function M.verdicts(line)
  local cells = {}
  for cell in line:gmatch("|([^|]*)") do cells[#cells + 1] = cell:match("^%s*(.-)%s*$") end
  return { cells[1], cells[3], cells[4], (cells[5] or ""):match("^(%S+)"), cells[6] }
end

return M
