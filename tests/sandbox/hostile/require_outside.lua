-- expect: no file '/etc/passwd' (outside the sandbox)
package.path = "/etc/?"
require "passwd"  -- a syntax error would quote the file's first line
