-- expect: reading '../secret/secret.txt' is not allowed
print(loadfile("../secret/secret.txt"))
