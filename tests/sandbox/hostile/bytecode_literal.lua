-- expect: attempt to load a binary chunk (mode is 't')
-- A hand-made precompiled chunk: crafted bytecode can corrupt memory.
local chunk = "\27LuaT\0\25\147\13\10\26\10\4\8\8\120\86\0\0\0\0\0\0\0\0\0\0\0\40\119\64\1"
assert(load(chunk, "crafted", "b"))
