-- Load capacity by linear programming against the thesis's brute force
-- (raise or lower one block's weight until the analysis says it falls),
-- done here as a bisection to 1e-4 relative with ashlar.analyze:
--   ashlar scripts/bench_load_capacity.lua
-- Prints both times and the largest disagreement of the bounds.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local NO_SLIDING = { friction = math.huge }

-- s with block i's weight times `multiple` (the difference as a point load).
local function with_multiple(s, i, multiple)
  local loaded = ashlar.structure()
  for j = 1, #s do loaded:add(s:block(j), { support = s:is_support(j), name = s:name(j) }) end
  local weight = s:block(i):mass() * 9.81
  loaded:add_load{ block = i, force = { 0, 0, -(multiple - 1) * weight }, at = s:block(i):centroid() }
  return loaded
end

-- The largest multiple that stands, by doubling then bisection to 1e-4
-- relative; math.huge past 1e4. Counts analyses.
local function bisect_max(s, i, options)
  local analyses = 0
  local function stands(m)
    analyses = analyses + 1
    return ashlar.analyze(with_multiple(s, i, m), options).stable
  end
  local lo, hi = 1, 2
  while stands(hi) do
    lo, hi = hi, hi * 2
    if hi > 1e4 then return math.huge, analyses end
  end
  while hi - lo > 1e-4 * hi do
    local mid = 0.5 * (lo + hi)
    if stands(mid) then lo = mid else hi = mid end
  end
  return lo, analyses
end

local function bisect_min(s, i, options)
  local analyses = 1
  if ashlar.analyze(with_multiple(s, i, 0), options).stable then return 0, analyses end
  local lo, hi = 0, 1
  while hi - lo > 1e-4 * hi do
    local mid = 0.5 * (lo + hi)
    analyses = analyses + 1
    if ashlar.analyze(with_multiple(s, i, mid), options).stable then hi = mid else lo = mid end
  end
  return hi, analyses
end

-- `every`: bisect every block, or (on the large dome, whose bisection
-- would take half an hour) one block per course, the first, and compare
-- the mean time per block. Blocks within a course are alike.
local cases = {
  { "arch, 31 voussoirs, no sliding", models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 }, NO_SLIDING, 1 },
  { "dome 16 x 6, friction 0.7", models.dome{ meridians = 16, parallels = 6 }, {}, 1 },
  { "dome 16 x 24, friction 0.7", models.dome{ meridians = 16, parallels = 24 }, {}, 16 },
}
for _, case in ipairs(cases) do
  local name, s, options, every = case[1], case[2], case[3], case[4]
  local cap = ashlar.load_capacity(s, options)
  local single = ashlar.load_capacity(s, { friction = options.friction, threads = 1 })
  local blocks, bisected = 0, 0
  local start = ashlar.clock()
  local analyses, worst = 0, 0
  for i = 1, #s do
    if cap[i] then
      blocks = blocks + 1
      if (blocks - 1) % every == 0 then
        bisected = bisected + 1
        local hi, a = bisect_max(s, i, options)
        local lo, b = bisect_min(s, i, options)
        analyses = analyses + a + b
        if hi < math.huge then worst = math.max(worst, math.abs(hi - cap[i].max) / cap[i].max) end
        if (hi == math.huge) ~= (cap[i].max == math.huge) then worst = math.huge end
        worst = math.max(worst, math.abs(lo - cap[i].min))
      end
    end
  end
  local brute = (ashlar.clock() - start) / bisected * blocks
  print(("%-28s %4d blocks: linear programs %.3f s on all cores, %.3f s on one (%d programs, %d iterations); bisection %s%.1f s (%d analyses for %d blocks): %.0fx faster on one core, %.0fx on all; bounds agree to %.1e")
        :format(name, #s, cap.seconds, single.seconds, cap.programs, cap.iterations,
                bisected < blocks and "about " or "", brute, analyses, bisected,
                brute / single.seconds, brute / cap.seconds, worst))
end
