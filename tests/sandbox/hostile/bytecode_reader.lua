-- expect: attempt to load a binary chunk (mode is 't')
local parts = { "\27Lua", "T\0" }
local i = 0
assert(load(function() i = i + 1; return parts[i] end, "pieces", "bt"))
