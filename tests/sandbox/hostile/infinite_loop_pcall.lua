-- expect: sandbox: time limit of 0.25 s exceeded
-- options: --time 0.25
-- Catching the limit's error does not help: it is raised again at every instruction.
while true do
  pcall(function() while true do pcall(function() while true do end end) end end)
end
