-- expect: db: sandbox: reading '/etc/passwd' is not allowed
local ashlar = require "ashlar"
ashlar.load_study{ db = "/etc/passwd", name = "s" }
