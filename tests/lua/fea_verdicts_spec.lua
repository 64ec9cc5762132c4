-- The FEA's verdict is the equilibrium method's with unlimited friction on
-- every model of the library it can mesh, and docs/verification.md's table
-- (written by scripts/fea_verdicts.lua) is the current one.
local cases = require "fea_verdict_cases"

local function committed_lines()
  local file = assert(io.open("../../docs/verification.md"))
  local lines = {}
  for line in file:lines() do
    local name = line:match("^| ([^|]-) | %d+ |")
    if name then lines[name] = line end
  end
  file:close()
  return lines
end

describe("the FEA's verdicts over the model library", function()
  local committed = committed_lines()
  for _, case in ipairs(cases.cases) do
    it(case[1], function()
      local row = cases.row(case)
      assert.are.equal(row.unlimited_friction, row.fea, "FEA against equilibrium with unlimited friction")
      assert.is_truthy(committed[case[1]], "no line for it in docs/verification.md")
      assert.are.same(cases.verdicts(committed[case[1]]), cases.verdicts(cases.table_line(row)))
    end)
  end
end)
