-- expect: writing '/tmp/ashlar-sandbox-pwned.txt' is not allowed
io.output("/tmp/ashlar-sandbox-pwned.txt")
io.write("pwned")
