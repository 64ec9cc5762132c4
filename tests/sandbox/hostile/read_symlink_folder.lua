-- expect: reading 'scripts/escape/secret.txt' is not allowed (it resolves to
-- scripts/escape is a symlink to ../secret, made by the spec.
print(assert(io.open("scripts/escape/secret.txt")):read("a"))
