-- expect: bad argument #1 to 'add' (Structure expected
local ashlar = require "ashlar"
local s = ashlar.structure()
local forged = setmetatable({}, { __index = function() return s end, __name = "ashlar.Structure" })
s.add(forged, ashlar.box{ size = { 1, 1, 1 } })
