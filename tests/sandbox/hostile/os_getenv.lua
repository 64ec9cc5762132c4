-- expect: os.getenv is not allowed in the sandbox
print(os.getenv("HOME"))
