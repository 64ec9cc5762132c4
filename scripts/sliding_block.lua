-- A rigid block sliding on a base shaken horizontally at a_g(t) = a sin(w t),
-- Coulomb friction mu, in closed form (Newmark 1965's sliding block, under
-- a harmonic ground acceleration): the block sticks to the base until
-- |a_g| exceeds mu g, then slips against a_g with relative acceleration
-- -a_g - mu g s (s the slip's sign) until its velocity relative to the
-- base is 0 again, where it sticks or, with |a_g| still above mu g, slips
-- back. Each slip in closed form, from its start t0:
--   v(t) = a / w (cos w t - cos w t0) - mu g s (t - t0)
--   x(t) = a / w^2 (sin w t - sin w t0) - a / w cos w t0 (t - t0) - mu g s (t - t0)^2 / 2
-- and its ends found by a scan of 0.1 ms (far below the motion's quarter
-- period) and bisection to rounding; nothing is integrated numerically.
-- tests/lua/simulate_spec.lua holds ashlar.simulate's sliding walls to it;
-- scripts/sliding_wall.lua prints the two side by side.
local M = {}

-- The block's displacement relative to the base at time T (s), in m, for
-- the ground's amplitude a (m/s^2) and circular frequency w (rad/s).
function M.displacement(a, w, mu, T, g)
  g = g or 9.81
  local function ground(t) return a * math.sin(w * t) end
  -- The first time after t, up to limit, at which past(time) holds; nil if none.
  local function first(t, past, limit)
    local hi = t + 1e-4
    while hi <= limit and not past(hi) do hi = hi + 1e-4 end
    if hi > limit then return nil end
    local lo = hi - 1e-4
    for _ = 1, 60 do
      local middle = 0.5 * (lo + hi)
      if past(middle) then hi = middle else lo = middle end
    end
    return hi
  end
  local t, x, slipping = 0, 0, false
  while t < T do
    local t0 = t
    if not slipping then
      t0 = first(t, function(u) return math.abs(ground(u)) > mu * g end, T)
      if not t0 then break end
    end
    local s = ground(t0) > 0 and -1 or 1
    local c0, s0 = math.cos(w * t0), math.sin(w * t0)
    local function velocity(u) return a / w * (math.cos(w * u) - c0) - mu * g * s * (u - t0) end
    local t1 = first(t0, function(u) return s * velocity(u) <= 0 end, T) or T
    x = x + a / w ^ 2 * (math.sin(w * t1) - s0) - a / w * c0 * (t1 - t0) - mu * g * s * (t1 - t0) ^ 2 / 2
    t, slipping = t1, math.abs(ground(t1)) > mu * g
  end
  return x
end

return M
