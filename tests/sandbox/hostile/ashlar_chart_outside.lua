-- expect: path: sandbox: writing '../pwned.png' is not allowed
local ashlar = require "ashlar"
ashlar.chart{ path = "../pwned.png", data = { { x = 1, y = 1 }, { x = 2, y = 2 } }, x = "x", y = "y" }
