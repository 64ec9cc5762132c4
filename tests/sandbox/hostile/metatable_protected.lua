-- expect: metatable: ashlar.Block, ashlar.Structure; setmetatable refused
-- exit: 0
-- getmetatable hides the methods and __gc of ashlar objects.
local ashlar = require "ashlar"
local b = ashlar.box{ size = { 1, 1, 1 } }
local s = ashlar.structure()
local refused = not pcall(setmetatable, b, {})
print(("metatable: %s, %s; setmetatable %s"):format(getmetatable(b), getmetatable(s), refused and "refused" or "allowed"))
