-- expect: scripts/memory_coroutine.lua:7: sandbox: memory limit of 64 MiB exceeded (the script's Lua heap)
-- options: --memory 64M
-- Out of memory in a coroutine: the place is where the main thread resumed it.
local grow = coroutine.wrap(function()
  local t = {} for i = 1, math.huge do t[i] = { i } end
end)
grow()
