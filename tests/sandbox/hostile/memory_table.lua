-- expect: sandbox: memory limit of 64 MiB exceeded
-- options: --memory 64M
local t = {}
for i = 1, math.huge do t[i] = { i } end
