-- expect: reading 'scripts/../secret/secret.txt' is not allowed
print(assert(io.open("scripts/../secret/secret.txt")):read("a"))
