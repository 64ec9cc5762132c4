-- expect: reading '/etc/passwd' is not allowed
io.input("/etc/passwd")
print(io.read("a"))
