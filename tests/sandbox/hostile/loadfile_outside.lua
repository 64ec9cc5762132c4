-- expect: reading '../secret/secret.txt' is not allowed
assert(loadfile("../secret/secret.txt"))
