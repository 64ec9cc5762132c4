-- expect: reading '/etc/passwd' is not allowed
for line in io.lines("/etc/passwd") do print(line) end
