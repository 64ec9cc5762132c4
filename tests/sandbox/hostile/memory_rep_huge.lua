-- expect: resulting string too large
print(#string.rep("x", 2^62))
