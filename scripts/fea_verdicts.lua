-- The FEA's verdict against the equilibrium method's over the model
-- library (tests/lua/fea_verdict_cases.lua): prints the table that
-- docs/verification.md carries, with the time it took.
--
--   ashlar scripts/fea_verdicts.lua
local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
package.path = here .. "/../tests/lua/?.lua;" .. package.path
local cases = require "fea_verdict_cases"

local clock = os.clock()
for _, line in ipairs(cases.header) do print(line) end
for _, case in ipairs(cases.cases) do print(cases.table_line(cases.row(case))) end
io.stderr:write(string.format("%.1f s of CPU\n", os.clock() - clock))
