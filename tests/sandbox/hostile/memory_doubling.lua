-- expect: scripts/memory_doubling.lua:4: sandbox: memory limit of 64 MiB exceeded
-- options: --memory 64M
local s = "x"
while true do s = s .. s end
