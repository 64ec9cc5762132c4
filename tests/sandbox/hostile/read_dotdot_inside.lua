-- expect: reading '../scripts/../secret/secret.txt' is not allowed
-- Out of the script's folder, back in, and out again.
print(assert(io.open("../scripts/../secret/secret.txt")):read("a"))
