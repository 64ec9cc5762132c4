-- expect: bad argument #1 to 'volume' (Block expected, got Structure)
local ashlar = require "ashlar"
local b = ashlar.box{ size = { 1, 1, 1 } }
local s = ashlar.structure()
b.volume(s)
