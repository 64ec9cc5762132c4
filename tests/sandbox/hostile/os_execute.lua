-- expect: os.execute is not allowed in the sandbox
os.execute("touch pwned")
