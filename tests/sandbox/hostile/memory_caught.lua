-- expect: caught 5 memory errors and went on
-- options: --memory 64M
-- exit: 0
-- A refused allocation is an ordinary error: a script may catch it and go on.
local caught = 0
for _ = 1, 5 do
  local ok = pcall(function() return string.rep("x", 100 * 2^20) end)
  if not ok then caught = caught + 1 end
end
print(("caught %d memory errors and went on"):format(caught))
