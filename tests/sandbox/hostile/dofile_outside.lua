-- expect: reading '/etc/passwd' is not allowed
dofile("/etc/passwd")  -- a syntax error would quote the file's first line
