-- expect: result: expected a Result of ashlar.analyze (not closed), got Result
local ashlar = require "ashlar"
local s = ashlar.structure()
s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, -0.5 } }, { support = true })
s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } })
local kept
do
  local r <close> = ashlar.analyze(s)
  kept = r
end
ashlar.export(s, "out/closed.obj", { result = kept })
print(kept.stable)
