-- expect: writing 'out/../pwned.txt' is not allowed
assert(io.open("out/../pwned.txt", "w")):write("pwned")
