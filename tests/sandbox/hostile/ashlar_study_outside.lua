-- expect: db: sandbox: writing '../secret/study.sqlite' is not allowed
local ashlar = require "ashlar"
ashlar.study{ name = "s", params = { t = { 1, 2 } }, db = "../secret/study.sqlite",
  run = function(p) return { t2 = p.t * 2 } end }
