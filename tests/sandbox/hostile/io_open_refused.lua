-- expect: nil	sandbox: reading '../secret/secret.txt' is not allowed (it resolves to
-- exit: 0
-- A refused io.open returns nil, why and an errno, as stock Lua does for a file the system refuses.
local file, message, code = io.open("../secret/secret.txt")
print(file, message)
assert(code == 13, "errno " .. tostring(code))
local removed, why, errno = os.remove("../secret/secret.txt")
assert(removed == nil and why:find("writing '../secret/secret.txt' is not allowed", 1, true) and errno == 13)
