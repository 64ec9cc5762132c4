-- expect: sandbox: time limit of 1 s exceeded
-- options: --time 1
-- Finalizers that never end, run by the collector and again at close.
for _ = 1, 100 do setmetatable({}, { __gc = function() while true do end end }) end
collectgarbage()
while true do end
