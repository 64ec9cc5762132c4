-- expect: attempt to use a closed Block
local ashlar = require "ashlar"
local kept
do
  local b <close> = ashlar.box{ size = { 1, 1, 1 } }
  kept = b
end
print(kept:volume())
