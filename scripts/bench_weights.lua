-- Time of each chapter-4 analysis (Shin 2014) on an arch of 31 voussoirs
-- (no sliding) and a dome of 16 x 24 blocks (friction 0.7):
--   ashlar scripts/bench_weights.lua
-- Prints one line per analysis and structure. The dome's important_weights
-- and load_capacity take minutes.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local cases = {
  { "arch, 31 voussoirs", models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 }, { friction = math.huge },
    "voussoir 8", "voussoir 16" },
  { "dome 16 x 24", models.dome{ meridians = 16, parallels = 24 }, {}, "course 12 block 1", "course 12 block 1" },
}

local function timed(what, f)
  local start = ashlar.clock()
  f()
  return what, ashlar.clock() - start
end

for _, case in ipairs(cases) do
  local name, s, options, block, loaded = case[1], case[2], case[3], case[4], case[5]
  local free = 0
  for i = 1, #s do if not s:is_support(i) then free = free + 1 end end
  print(("%s (%d free blocks)"):format(name, free))
  local analysis = ashlar.analyze(s, options)
  local sensitivity = ashlar.weight_sensitivity(s, loaded, options)
  print(("  %-26s %9.4f s  (after the analysis, %.3f s)"):format("weight_sensitivity", sensitivity.seconds,
                                                                    analysis.seconds))
  for _, run in ipairs{
    { timed("necessary_weights", function() ashlar.necessary_weights(s, block, options) end) },
    { timed("important_weights", function() ashlar.important_weights(s, options) end) },
    { timed("trace_loads, 200 traces", function() ashlar.trace_loads(s, loaded, { traces = 200, seed = 1 }) end) },
    { timed("load_capacity", function() ashlar.load_capacity(s, options) end) },
  } do
    print(("  %-26s %9.4f s"):format(run[1], run[2]))
  end
end
