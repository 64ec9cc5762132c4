-- expect: os.tmpname is not allowed in the sandbox
print(os.tmpname())
