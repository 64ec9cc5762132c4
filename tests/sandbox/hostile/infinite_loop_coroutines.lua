-- expect: sandbox: time limit of 0.25 s exceeded
-- options: --time 0.25
local spinners = {}
for i = 1, 10 do
  spinners[i] = coroutine.wrap(function() while true do pcall(coroutine.yield) end end)
end
while true do for _, spin in ipairs(spinners) do pcall(spin) end end
