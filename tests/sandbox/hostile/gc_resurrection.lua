-- expect: resurrected 100 closed blocks safely
-- exit: 0
-- Objects that come back from collection through a table's finalizer are
-- still valid or reported as closed, never freed memory.
local ashlar = require "ashlar"
local saved = {}
for i = 1, 100 do
  local b = ashlar.box{ size = { 1, 1, 1 } }
  setmetatable({}, { __gc = function() saved[#saved + 1] = b end })
  if i % 2 == 0 then local c <close> = b end
end
b = nil
collectgarbage(); collectgarbage()
local ok = 0
for _, b in ipairs(saved) do
  local fine, message = pcall(b.volume, b)
  if fine or tostring(message):find("closed", 1, true) then ok = ok + 1 end
end
print(("resurrected %d closed blocks safely"):format(ok))
