-- expect: sandbox: a path may not contain a zero byte
-- The file a C function opens ends at a zero byte: the whole path is refused.
assert(io.open("data.txt\0/../../secret/secret.txt"))
