-- expect: reading 'scripts/passwd' is not allowed (it resolves to '/etc/passwd')
-- scripts/passwd is a symlink to /etc/passwd, made by the spec.
print(assert(io.open("scripts/passwd")):read("a"))
