-- expect: not enough memory
-- options: --engine-memory 200M
-- unless: AddressSanitizer
-- The process as a whole (engine included) is capped, not only the Lua heap:
-- these models hold 4 MiB of Lua and about a gigabyte of blocks. (An
-- AddressSanitizer build maps its memory as it goes, so it sets no cap.)
local models = require "ashlar.models"
local keep = {}
for i = 1, 40 do keep[i] = models.arch{ voussoirs = 20000 } end
print("not capped")
