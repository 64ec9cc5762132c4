-- expect: path: sandbox: reading '../secret/secret.txt' is not allowed
local ashlar = require "ashlar"
ashlar.load("../secret/secret.txt")
