-- expect: writing 'pwned.lua' is not allowed
-- The script's folder is readable, not writable: a script may not rewrite its neighbours.
assert(io.open("pwned.lua", "w")):write("os.execute('touch pwned')")
