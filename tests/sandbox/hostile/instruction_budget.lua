-- expect: sandbox: instruction budget of 1000000 exceeded
-- options: --instructions 1e6
local n = 0
while true do n = n + 1 end
