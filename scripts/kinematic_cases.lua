-- Structures where rigid-block equilibrium is known to be wrong or right,
-- for the kinematic method's checks: tests/lua/kinematic_spec.lua asserts
-- on them, scripts/compare_methods.lua tabulates them.
--   local cases = dofile("scripts/kinematic_cases.lua")
local ashlar = require "ashlar"

local cases = {}
local Y = { 0, 1, 0 }

-- A block set between two walls (supports), nothing under it.
function cases.clamped()
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 1, 1, 2 }, center = { -0.5, 0, 1 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 2 }, center = { 1.5, 0, 1 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.5, 0, 1.5 } })
  return s
end

-- A wedge (height 0.6 m, 0.4 m wide at the bottom) seated in a V whose faces
-- are 15 degrees from vertical, the wedge wider at the top.
function cases.wedge()
  local h, bottom = 0.6, 0.4
  local top = bottom + 2 * h * math.tan(math.rad(15))
  local s = ashlar.structure()
  s:add(ashlar.prism({ { -bottom / 2, 0, 0 }, { -top / 2, 0, h }, { -2, 0, h }, { -2, 0, 0 } }, Y), { support = true })
  s:add(ashlar.prism({ { bottom / 2, 0, 0 }, { 2, 0, 0 }, { 2, 0, h }, { top / 2, 0, h } }, Y), { support = true })
  s:add(ashlar.prism({ { -bottom / 2, 0, 0 }, { bottom / 2, 0, 0 }, { top / 2, 0, h }, { -top / 2, 0, h } }, Y))
  return s
end

-- A flat arch of five 0.5 m voussoirs, 0.4 m deep, between two fixed
-- abutments: joints vertical (c nil), or converging to a point c metres
-- below its soffit.
function cases.flat_arch(c)
  local depth, count, width = 0.4, 5, 0.5
  local function top(x) return c and x * (1 + depth / c) or x end
  local s, x0 = ashlar.structure(), -count * width / 2
  s:add(ashlar.prism({ { x0, 0, 0 }, { top(x0), 0, depth }, { x0 - 1.5, 0, depth }, { x0 - 1.5, 0, 0 } }, Y),
    { support = true })
  s:add(ashlar.prism({ { -x0, 0, 0 }, { -x0 + 1.5, 0, 0 }, { -x0 + 1.5, 0, depth }, { top(-x0), 0, depth } }, Y),
    { support = true })
  for k = 0, count - 1 do
    local a, b = x0 + k * width, x0 + (k + 1) * width
    s:add(ashlar.prism({ { a, 0, 0 }, { b, 0, 0 }, { top(b), 0, depth }, { top(a), 0, depth } }, Y))
  end
  return s
end

-- A block (1 x 1 x 0.5 m) on a slab tilted by theta about y: it slides
-- towards +x.
function cases.incline(theta)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 4, 2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.25 } })
  return ashlar.tilt(s, theta, { origin = { 0, 0, 0 } })
end

-- Two unit blocks on a support's edge, the harmonic overhangs 1/4 and 3/4
-- scaled by f: stands for f < 1, tips for f > 1.
function cases.stack(f)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { -0.5, 0, -0.25 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { f * 0.25 - 0.5, 0, 0.1 } })
  s:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { f * 0.75 - 0.5, 0, 0.3 } })
  return s
end

return cases
