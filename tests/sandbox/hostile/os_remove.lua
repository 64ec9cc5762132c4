-- expect: writing '../secret/secret.txt' is not allowed
assert(os.remove("../secret/secret.txt"))
