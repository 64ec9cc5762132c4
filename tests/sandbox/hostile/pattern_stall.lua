-- expect: stuck in C code); process ended
-- options: --time 0.25
-- A pathological pattern keeps Lua inside one C call, where no hook runs:
-- the process's hard deadline ends it.
print(string.rep("a", 1e4):find(".-.-.-.-.-.-b"))
