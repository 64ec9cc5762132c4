-- expect: reading 'passwd' is not allowed (it resolves to '/etc/passwd')
-- passwd, beside the script, is a symlink to /etc/passwd, made by the spec.
print(assert(io.open("passwd")):read("a"))
