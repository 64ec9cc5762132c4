-- expect: sandbox: time limit of 1 s exceeded
-- options: --time 1
while true do end
