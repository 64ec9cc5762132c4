-- expect: 4 rows, 4 errors: sandbox: reading '/etc/passwd' is not allowed
-- exit: 0
-- A study's worker threads run the script in sandboxed states too.
local ashlar = require "ashlar"
local st = ashlar.study{ name = "peek", params = { k = { 1, 2, 3, 4 } }, workers = 2, progress = false,
  run = function(p) return { text = assert(io.open("/etc/passwd")):read("a") } end }
local errors, message = 0, nil
for _, row in ipairs(st:rows()) do
  if row.run_status == "error" then errors = errors + 1; message = row.run_error end
end
print(("%d rows, %d errors: %s"):format(#st:rows(), errors, message:match("sandbox: .-allowed")))
