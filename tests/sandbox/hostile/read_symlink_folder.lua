-- expect: reading 'escape/secret.txt' is not allowed (it resolves to
-- escape, beside the script, is a symlink to ../secret, made by the spec.
print(assert(io.open("escape/secret.txt")):read("a"))
