-- expect: path: sandbox: writing '/tmp/ashlar-sandbox-pwned.obj' is not allowed
local ashlar = require "ashlar"
local s = ashlar.structure()
s:add(ashlar.box{ size = { 1, 1, 1 } })
ashlar.export(s, "/tmp/ashlar-sandbox-pwned.obj")
