-- expect: sandbox: time limit of 0.25 s exceeded
-- options: --time 0.25
while true do xpcall(function() while true do end end, function() while true do end end) end
