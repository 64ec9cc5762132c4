-- expect: writing '../secret/secret.txt' is not allowed
assert(io.open("../secret/secret.txt", "r+")):write("overwritten")
