-- expect: sandbox: time limit of 0.25 s exceeded
-- options: --time 0.25
local function forever(n) return forever(n + 1) end
forever(0)
