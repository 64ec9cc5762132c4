-- The rocking of a free-standing rectangular block under a one-sine pulse of
-- ground acceleration, a_g(t) = a_p sin(w_p t) for 0 <= t <= 2 pi / w_p and 0
-- after, as Zhang and Makris solve it in closed form:
--   J. Zhang, N. Makris (2001), "Rocking response of free-standing blocks
--   under cycloidal pulses", J. Eng. Mech. 127(5), 473-483.
-- The block (half-width b, half-height h, R = sqrt(b^2 + h^2), slenderness
-- alpha = atan(b / h), frequency parameter p = sqrt(3 g / (4 R))) stays at
-- rest until the ground's acceleration reaches Housner's uplift threshold
-- g tan(alpha) (Housner 1963), then rocks about one base edge. The linearised
-- equation of a slender block, theta'' = p^2 (theta - alpha sgn(theta) +
-- a_g / g), has on each side between impacts the closed-form solution
--   theta(t) = alpha s - A sin(w_p t) + C1 cosh(p tau) + C2 sinh(p tau),
--   A = (a_p / g) p^2 / (p^2 + w_p^2) during the pulse, 0 after it,
-- (tau the time since the segment began), and an impact (theta = 0) keeps
-- the angular momentum about the edge that strikes: the angular velocity
-- is multiplied by Housner's r = 1 - 3/2 sin^2(alpha). Once the pulse is
-- over, the block overturns if and only if it escapes over its edge,
-- (theta - alpha s) s + theta' s / p > 0, or does so after its next impact.
-- Events (impacts, the pulse's end) are found on the closed form by
-- bracketing and bisection; nothing is integrated numerically.
local M = {}

local g = 9.81

-- The block's parameters from its full width and height (m).
function M.block(width, height)
  local b, h = width / 2, height / 2
  local R = math.sqrt(b * b + h * h)
  local alpha = math.atan(b, h)
  return {
    alpha = alpha,
    R = R,
    p = math.sqrt(3 * g / (4 * R)),
    r = 1 - 1.5 * math.sin(alpha) ^ 2,
    threshold = g * math.tan(alpha),   -- Housner's uplift acceleration (m/s^2)
  }
end

-- Rotation and its rate at time t of a segment started at t0 from
-- (theta0, omega0) on side s, under the pulse (amplitude A in rad, w) or
-- after it (A = 0).
local function segment(block, s, t0, theta0, omega0, A, w)
  local p, alpha = block.p, block.alpha
  local c1 = theta0 - alpha * s + A * math.sin(w * t0)
  local c2 = (omega0 + A * w * math.cos(w * t0)) / p
  return function(t)
    local tau = t - t0
    local ch, sh = math.cosh(p * tau), math.sinh(p * tau)
    return alpha * s - A * math.sin(w * t) + c1 * ch + c2 * sh,
           -A * w * math.cos(w * t) + p * (c1 * sh + c2 * ch)
  end
end

-- The first time in (t0, t1] where theta crosses 0 on side s, or nil:
-- sampled every `dt`, then bisected to 1e-12 s.
local function first_crossing(theta_of, s, t0, t1, dt)
  local a = t0
  while a < t1 do
    local b = math.min(a + dt, t1)
    if s * theta_of(b) <= 0 then
      local lo, hi = a, b
      while hi - lo > 1e-12 do
        local mid = 0.5 * (lo + hi)
        if s * theta_of(mid) <= 0 then hi = mid else lo = mid end
      end
      return hi
    end
    a = b
  end
  return nil
end

-- Whether the block overturns under the pulse of amplitude ap (m/s^2) and
-- circular frequency w (rad/s), and the number of impacts before the pulse
-- ended.
function M.overturns(block, ap, w)
  local T = 2 * math.pi / w
  local A = (ap / g) * block.p ^ 2 / (block.p ^ 2 + w * w)
  local dt = math.min(T, 2 * math.pi / block.p) / 400
  -- At rest until |a_g| first reaches the threshold.
  local function uplift(from)
    local t = from
    while t < T do
      local a = ap * math.sin(w * t)
      if math.abs(a) >= block.threshold then return t, a > 0 and 1 or -1 end
      t = t + dt / 20
    end
    return nil
  end
  local t, s = uplift(0)
  if not t then return false, 0 end
  local theta, omega, impacts = 0, 0, 0
  while true do
    local theta_of = segment(block, s, t, theta, omega, A, w)
    local hit = first_crossing(theta_of, s, t + 1e-12, T, dt)
    if not hit then
      theta, omega = theta_of(T)
      break
    end
    local _, rate = theta_of(hit)
    impacts = impacts + 1
    if math.abs(rate) * block.r < 1e-9 then
      -- Stopped by the impact: at rest until the ground lifts it again.
      t, s = uplift(hit)
      if not t then return false, impacts end
      theta, omega = 0, 0
    else
      t, theta, omega, s = hit, 0, rate * block.r, -s
    end
  end
  -- After the pulse: escape over the edge on side s, or after the next impact.
  local p, alpha = block.p, block.alpha
  if (theta - alpha * s) * s + omega * s / p > 0 then return true, impacts end
  local speed = math.sqrt(math.max(0, omega * omega - p * p * (theta - alpha * s) ^ 2 + p * p * alpha * alpha))
  return block.r * speed / p > alpha, impacts
end

-- The amplitudes (m/s^2) in [lo, hi] where the verdict changes, found on a
-- scan of `count` amplitudes and bisected to a relative 1e-6: the first is
-- the minimum overturning acceleration (nil when none overturns).
function M.transitions(block, w, lo, hi, count)
  local found = {}
  local previous = M.overturns(block, lo, w)
  local last = lo
  for k = 1, count do
    local ap = lo + (hi - lo) * k / count
    local verdict = M.overturns(block, ap, w)
    if verdict ~= previous then
      local a, b = last, ap
      while b - a > 1e-6 * b do
        local mid = 0.5 * (a + b)
        if M.overturns(block, mid, w) == previous then a = mid else b = mid end
      end
      found[#found + 1] = { amplitude = b, overturns = verdict }
      previous = verdict
    end
    last = ap
  end
  return found
end

-- The same block simulated by ashlar: a width x depth x height box (m) on a
-- fixed slab, under the pulse along x (ap in m/s^2, w in rad/s), run until
-- `after` seconds past the pulse (default 2.5 periods 2 pi / p of the block's
-- rocking, long enough to fall). Returns whether it collapsed (the Simulation's
-- summary: its centroid dropped by half its width), its peak displacement (m),
-- the time it first moved (nil if it never did) and the Simulation.
function M.simulate(width, height, depth, ap, w, opts)
  local ashlar = require "ashlar"
  opts = opts or {}
  local s = ashlar.structure()
  -- A slab long enough for the block to lie down on either side.
  s:add(ashlar.box{ size = { 3 * height, 2 * depth, 0.1 }, center = { 0, 0, -0.05 } }, { support = true })
  s:add(ashlar.box{ size = { width, depth, height }, center = { 0, 0, height / 2 } })
  local T = 2 * math.pi / w
  local block = M.block(width, height)
  local sim = ashlar.simulate(s, {
    duration = T + (opts.after or 2.5 * 2 * math.pi / block.p),
    step = opts.step or 1e-3,
    friction = 0.8,   -- no sliding: a_g / g stays below 0.8 over the grid
    ground_acceleration = function(t)
      if t > T then return 0, 0, 0 end
      return ap * math.sin(w * t), 0, 0
    end,
  })
  local summary = sim:summary()
  return summary.collapsed, summary.peak_displacement, summary.first_movement, sim
end

return M
