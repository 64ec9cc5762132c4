-- Whether contact detection depends on how a joint is turned: two boxes
-- 0.20 x 0.06 x 0.10 m, the lower a support, the upper resting on it flush
-- across the whole 0.20 x 0.06 m face (a 6 cm wide joint), both turned about
-- z from 0 to 90 degrees in 5 degree steps, at contact tolerances 0.01 to
-- 0.10 m. Prints one row per angle: the number of interfaces at each
-- tolerance, then the verdicts (S stands, F floats or falls).
--
--   build/bin/ashlar scripts/contact_turning.lua
local ashlar = require "ashlar"

local tolerances = {}
for k = 1, 10 do tolerances[k] = k / 100 end

local header = { "angle" }
for _, t in ipairs(tolerances) do header[#header + 1] = ("%.2f"):format(t) end
print(table.concat(header, "\t") .. "\tverdicts")
local lost = 0
for degrees = 0, 90, 5 do
  local angle = math.rad(degrees)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 0.20, 0.06, 0.10 }, center = { 0, 0, -0.05 } }:rotated({ 0, 0, 1 }, angle), { support = true })
  s:add(ashlar.box{ size = { 0.20, 0.06, 0.10 }, center = { 0, 0, 0.05 } }:rotated({ 0, 0, 1 }, angle))
  local row, verdicts = { tostring(degrees) }, {}
  for _, t in ipairs(tolerances) do
    local count = #s:interfaces{ tolerance = t }
    row[#row + 1] = tostring(count)
    if count == 0 then lost = lost + 1 end
    verdicts[#verdicts + 1] = ashlar.analyze(s, { contact_tolerance = t }).stable and "S" or "F"
  end
  print(table.concat(row, "\t") .. "\t" .. table.concat(verdicts))
end
print(("joint lost in %d of %d cases"):format(lost, 19 * #tolerances))
