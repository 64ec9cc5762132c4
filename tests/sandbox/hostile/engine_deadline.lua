-- expect: sandbox: time limit of 0.25 s exceeded
-- options: --time 0.25
-- A long solve in C++ stops at the deadline (the engine polls it), and the
-- script ends with the limit even though it runs few instructions after.
local models = require "ashlar.models"
local ashlar = require "ashlar"
local r = ashlar.analyze(models.dome{ meridians = 64, parallels = 64 })
print(r.status)
