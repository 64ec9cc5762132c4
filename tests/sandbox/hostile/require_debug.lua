-- expect: module 'debug' not found
local d = require "debug"
d.sethook()
