-- expect: path: sandbox: reading '/etc/passwd' is not allowed
local ashlar = require "ashlar"
ashlar.import("/etc/passwd")
