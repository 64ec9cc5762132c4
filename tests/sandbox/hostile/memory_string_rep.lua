-- expect: scripts/memory_string_rep.lua:3: sandbox: memory limit of 64 MiB exceeded
-- options: --memory 64M
local bomb = string.rep("x", 100 * 2^20)
print(#bomb)
