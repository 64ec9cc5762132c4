-- expect: reading '../secret/secret.txt' is not allowed (it resolves to
print(assert(io.open("../secret/secret.txt")):read("a"))
