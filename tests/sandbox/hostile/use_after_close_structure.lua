-- expect: attempt to use a closed Structure
local ashlar = require "ashlar"
local kept
do
  local s <close> = ashlar.structure()
  kept = s
end
kept:add(ashlar.box{ size = { 1, 1, 1 } })
