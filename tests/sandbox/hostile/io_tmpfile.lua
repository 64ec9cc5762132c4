-- expect: io.tmpfile is not allowed in the sandbox
io.tmpfile():write("x")
