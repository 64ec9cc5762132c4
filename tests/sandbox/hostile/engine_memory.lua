-- expect: not enough memory
-- options: --engine-memory 200M
-- The process as a whole (engine included) is capped, not only the Lua heap.
local models = require "ashlar.models"
print(#models.arch{ voussoirs = 2000000 })
