-- expect: path: sandbox: writing '../pwned.svg' is not allowed
local ashlar = require "ashlar"
local s = ashlar.structure()
s:add(ashlar.box{ size = { 1, 1, 1 } })
ashlar.draw(s, "../pwned.svg")
