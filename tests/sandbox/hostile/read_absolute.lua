-- expect: reading '/etc/passwd' is not allowed
print(assert(io.open("/etc/passwd")):read("a"))
