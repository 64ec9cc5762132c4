-- expect: sandbox: time limit of 0.25 s exceeded
-- options: --time 0.25
-- Finalizers that never end, run by the collector and again at close.
for _ = 1, 100 do setmetatable({}, { __gc = function() while true do end end }) end
collectgarbage()
while true do end
