-- expect: package.searchpath is not allowed in the sandbox
print(package.searchpath("passwd", "/etc/?"))  -- would probe for files anywhere
