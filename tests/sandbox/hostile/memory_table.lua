-- expect: scripts/memory_table.lua:4: sandbox: memory limit of 64 MiB exceeded (the script's Lua heap)
-- options: --memory 64M
local t = {}
for i = 1, math.huge do t[i] = { i } end
