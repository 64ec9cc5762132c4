-- expect: ashlar.sandbox is not allowed inside a sandbox
local ashlar = require "ashlar"
ashlar.sandbox{ source = "os.execute('touch pwned')", read = { "/" }, write = { "/" } }
