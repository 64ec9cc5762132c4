-- expect: sandbox: time limit of 1 s exceeded
-- options: --time 1
local function forever(n) return forever(n + 1) end
forever(0)
