-- expect: path: sandbox: writing '../secret/model.json' is not allowed
local ashlar = require "ashlar"
local s = ashlar.structure()
s:add(ashlar.box{ size = { 1, 1, 1 } })
s:save("../secret/model.json")
