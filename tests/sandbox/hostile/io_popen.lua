-- expect: io.popen is not allowed in the sandbox
print(io.popen("cat ../secret/secret.txt"):read("a"))
