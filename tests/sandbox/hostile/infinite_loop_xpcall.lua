-- expect: sandbox: time limit of 1 s exceeded
-- options: --time 1
while true do xpcall(function() while true do end end, function() while true do end end) end
