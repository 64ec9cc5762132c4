-- expect: writing '../secret/stolen.txt' is not allowed
assert(io.open("out/note.txt", "w")):close()
assert(os.rename("out/note.txt", "../secret/stolen.txt"))
