-- expect: the string metatable is the script's own
-- exit: 0
-- Changing the shared string metatable only changes this script's state.
getmetatable("").__index = function() return function() return "hijacked" end end
local ashlar = require "ashlar"
local b = ashlar.box{ size = { 2, 1, 1 } }
assert(b:volume() == 2)
print(("x"):anything() == "hijacked" and "the string metatable is the script's own")
