-- expect: writing 'out/link/secret.txt' is not allowed (it resolves to
-- out/link is a symlink to ../../secret, made by the spec.
assert(io.open("out/link/secret.txt", "w")):write("overwritten")
