-- expect: sandbox: memory limit of 64 MiB exceeded
-- options: --memory 64M
collectgarbage("stop")
local keep = {}
for i = 1, math.huge do keep[#keep + 1] = ("%d"):format(i):rep(100) end
