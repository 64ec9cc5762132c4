-- "Where methods fail": structures at the edge of standing, probed with
-- ashlar.analyze, ashlar.load_factor and ashlar.friction_demand. Shared by
-- tests/lua/edge_cases_spec.lua (which asserts every row) and
-- scripts/edge_cases.lua (which prints the pass table and measures how close
-- to the edge each method stays right).
--
-- Every case has an answer from an independent method: closed-form statics
-- (a stack of boxes is statically determinate: the line of action of the
-- load above each joint must cross it inside the contact; a block on an
-- incline slides when mu < tan(alpha)), a thrust-line calculation for the
-- arch's minimum thickness (its own little linear program in the crown
-- thrust, solved here in Lua), the documented contact rule, and the same
-- model at another scale. A method passes a case when it gives the right
-- answer, or says that it cannot: analyze with `borderline` or an unstable
-- verdict that did not converge, load_factor and friction_demand with
-- "stopped" or "numerical difficulties". A wrong answer with a confident
-- status fails.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local M = {}

-- How close an answer must be to the reference.
M.tolerance = {
  factor = 1e-7,           -- load factor, absolute (in g) ...
  factor_relative = 1e-6,  -- ... plus this fraction of the reference
  demand_relative = 2e-6,  -- friction demand (its bracket is 1e-6 wide)
  scale_relative = 1e-6,   -- the same answer at another scale
}

-- Perturbations around each edge: the exact edge, then both sides.
M.deltas = { -1e-2, -1e-4, -1e-6, 0, 1e-6, 1e-4, 1e-2 }

local NO_SLIDING = math.huge

local function g(x) return ("%.10g"):format(x) end

------------------------------------------------------------------------
-- Independent references
------------------------------------------------------------------------

-- A stack of boxes (planar, equal depth and density), bottom to top, each
-- { x = centre, b = width, h = height }, on a ground wider than the lowest.
-- Returns the interval [lo, hi] of lateral body-force factors (load lambda
-- times each weight along +x) with which it stands: at every joint the
-- resultant of the blocks above, (lambda W, -W) through their centroid, must
-- cross the joint inside the contact; sliding bounds |lambda| by friction
-- (every joint is horizontal). lo > hi: it stands with no lateral load.
function M.stack_factor(boxes, friction)
  local lo, hi = -math.huge, math.huge
  local top = { [0] = 0 }
  for i, box in ipairs(boxes) do top[i] = top[i - 1] + box.h end
  for j = 0, #boxes - 1 do  -- the joint under block j + 1 (j = 0: the ground)
    local above = boxes[j + 1]
    local left, right = above.x - above.b / 2, above.x + above.b / 2
    if j > 0 then
      left = math.max(left, boxes[j].x - boxes[j].b / 2)
      right = math.min(right, boxes[j].x + boxes[j].b / 2)
    end
    local weight, moment_x, moment_z = 0, 0, 0
    for k = j + 1, #boxes do
      local w = boxes[k].b * boxes[k].h
      weight = weight + w
      moment_x = moment_x + w * boxes[k].x
      moment_z = moment_z + w * (top[k - 1] + boxes[k].h / 2)
    end
    local x, height = moment_x / weight, moment_z / weight - top[j]
    lo = math.max(lo, (left - x) / height)
    hi = math.min(hi, (right - x) / height)
  end
  return math.max(lo, -friction), math.min(hi, friction)
end

-- The load factor of a stack (hi), or "infeasible" when no lateral load
-- lets it stand.
local function stack_expected_factor(boxes, friction)
  local lo, hi = M.stack_factor(boxes, friction)
  if lo > hi then return "infeasible" end
  return hi
end

-- Area and centroid (x, z) of a polygon {{x, z}, ...}.
local function polygon_area(points)
  local area, cx, cz = 0, 0, 0
  for i = 1, #points do
    local p, q = points[i], points[i % #points + 1]
    local cross = p[1] * q[2] - q[1] * p[2]
    area = area + cross
    cx = cx + (p[1] + q[1]) * cross
    cz = cz + (p[2] + q[2]) * cross
  end
  return math.abs(area / 2), cx / (3 * area), cz / (3 * area)
end

-- Thrust-line test of a semicircular arch (centreline radius R, thickness
-- t, N voussoirs, N even, radial joints, straight intrados and extrados
-- chords as models.arch builds them; no sliding). By symmetry a
-- compression-only equilibrium exists iff a symmetric one does: a
-- horizontal crown thrust a at height z0 (b = a z0) whose line of action,
-- with the weight of the voussoirs from the crown down, crosses every joint
-- of the right half between intrados and extrados. Each joint gives two
-- inequalities linear in (a, b), so the largest slack over a, a concave
-- piecewise linear function, says whether the arch stands: returned over
-- the half arch's weight times R (negative: it falls).
function M.arch_slack(R, t, N)
  assert(N % 2 == 0, "arch_slack: an even number of voussoirs")
  local inner, outer = R - t / 2, R + t / 2
  local function joint(j)
    if j == N then return 1, 0 end          -- the springing is exactly horizontal
    if j == N / 2 then return 0, 1 end      -- the crown exactly vertical
    local angle = math.pi - j * math.pi / N
    return math.cos(angle), math.sin(angle)
  end
  local lines = {}  -- b >= s_lo a + c_lo and b <= s_hi a + c_hi
  local weight, moment = 0, 0
  for j = N / 2, N do
    local c, s = joint(j)
    if j > N / 2 then
      local c0, s0 = joint(j - 1)
      local area, x = polygon_area{ { inner * c0, inner * s0 }, { outer * c0, outer * s0 },
                                    { outer * c, outer * s }, { inner * c, inner * s } }
      weight, moment = weight + area, moment + area * x
    end
    lines[#lines + 1] = { inner * s, inner * c * weight - moment, outer * s, outer * c * weight - moment }
  end
  local function slack(a)
    local lower, upper = -math.huge, math.huge
    for _, l in ipairs(lines) do
      lower = math.max(lower, l[1] * a + l[2])
      upper = math.min(upper, l[3] * a + l[4])
    end
    return upper - lower
  end
  local lo, hi = 0, 100 * weight * R / t  -- past hi the line misses the springing
  for _ = 1, 200 do  -- ternary search on a concave function
    local m1, m2 = lo + (hi - lo) / 3, hi - (hi - lo) / 3
    if slack(m1) < slack(m2) then lo = m1 else hi = m2 end
  end
  return slack((lo + hi) / 2) / (weight * R)
end

-- The minimum thickness of that arch by regula falsi (Illinois) on the
-- slack, to `tolerance` relative (1e-14 by default).
local threshold_cache = {}
function M.arch_threshold(R, N, tolerance)
  tolerance = tolerance or 1e-14
  local key = ("%.17g/%d/%g"):format(R, N, tolerance)
  if threshold_cache[key] then return threshold_cache[key] end
  local lo, hi = 0.05 * R, 0.2 * R
  local s_lo, s_hi = M.arch_slack(R, lo, N), M.arch_slack(R, hi, N)
  assert(s_lo < 0 and s_hi > 0, "arch_threshold: no threshold in [0.05 R, 0.2 R]")
  local side = 0
  for _ = 1, 300 do
    local t = (lo * s_hi - hi * s_lo) / (s_hi - s_lo)
    local s = M.arch_slack(R, t, N)
    if s < 0 then
      lo, s_lo = t, s
      if side < 0 then s_hi = s_hi / 2 end
      side = -1
    else
      hi, s_hi = t, s
      if side > 0 then s_lo = s_lo / 2 end
      side = 1
    end
    if hi - lo <= tolerance * hi then break end
  end
  threshold_cache[key] = (lo + hi) / 2
  return threshold_cache[key]
end

-- Load factor of a block on an incline of angle alpha (descending towards
-- +x) with friction mu, under a horizontal body force along +x: it slides
-- when the resultant leaves the friction cone, tan(atan(mu) - alpha).
function M.incline_factor(alpha, mu)
  return math.tan(math.atan(mu) - alpha)
end

------------------------------------------------------------------------
-- Builders (lengths times `scale`)
------------------------------------------------------------------------

-- A planar stack of boxes (see M.stack_factor) of depth `depth`, on a
-- ground slab under the lowest block (twice its width): block 1 is the
-- ground, so every contact polygon lies in the lower block's plane.
local function stack_of(boxes, scale, depth)
  scale, depth = scale or 1, depth or 1
  local s = ashlar.structure()
  local base = boxes[1]
  s:add(ashlar.box{ size = { 2 * base.b * scale, 2 * depth * scale, 0.5 * scale },
                    center = { base.x * scale, 0, -0.25 * scale } }, { support = true, name = "ground" })
  local z = 0
  for i, box in ipairs(boxes) do
    s:add(ashlar.box{ size = { box.b * scale, depth * scale, box.h * scale },
                      center = { box.x * scale, 0, (z + box.h / 2) * scale } }, { name = ("block %d"):format(i) })
    z = z + box.h
  end
  s:set_planar(true)
  return s
end

-- A 1 x 0.6 x 0.2 block on a 3 m slab, both turned by alpha about y (the
-- slope descends towards +x); the contact is 1 m along the slope, so the
-- friction pyramid has an edge along the slip.
local function incline(alpha, scale)
  local s = ashlar.structure()
  local axis, origin = { 0, 1, 0 }, { 0, 0, 0 }
  s:add(ashlar.box{ size = { 3 * scale, 1 * scale, 0.2 * scale }, center = { 0, 0, -0.1 * scale } }
    :rotated(axis, alpha, origin), { support = true, name = "incline" })
  s:add(ashlar.box{ size = { 1 * scale, 0.6 * scale, 0.2 * scale }, center = { 0, 0, 0.1 * scale } }
    :rotated(axis, alpha, origin), { name = "block" })
  s:set_planar(true)
  return s
end

local function scaled_text(scale)
  if scale == 1 then return "" end
  return (" at scale %g"):format(scale)
end

------------------------------------------------------------------------
-- Families: one structure per perturbation delta of the edge
------------------------------------------------------------------------

local INCLINE = 0.3  -- rad
local HARMONIC = 5   -- blocks
local TOWER = 100    -- drums
local ARCH_N = 24

M.families = {
  {
    key = "stack",
    name = "Stack at the tipping point",
    what = "two 1 x 0.5 m blocks, the top one overhanging by b/2 (1 + d); falls for d > 0",
    falls = 1,  -- the sign of delta on which it falls
    boxes = function(delta)
      return { { x = 0, b = 1, h = 0.5 }, { x = 0.5 * (1 + delta), b = 1, h = 0.5 } }
    end,
    options = {},
  },
  {
    key = "harmonic",
    name = "Harmonic stack, every joint at its limit",
    what = "5 blocks 1 x 0.5 m, block k + 1 offset b / (2 (5 - k)) (1 + d) on block k; falls for d > 0",
    falls = 1,
    build = function(delta, scale)
      local offsets = {}
      for k = 1, HARMONIC - 1 do offsets[k] = scale * (1 + delta) / (2 * (HARMONIC - k)) end
      return models.stack{ blocks = HARMONIC, size = { scale, scale, 0.5 * scale }, offsets = offsets }
    end,
    boxes = function(delta)
      local boxes, x = {}, 0
      for k = 1, HARMONIC do
        boxes[k] = { x = x, b = 1, h = 0.5 }
        if k < HARMONIC then x = x + (1 + delta) / (2 * (HARMONIC - k)) end
      end
      return boxes
    end,
    options = {},
  },
  {
    key = "tower",
    name = "Leaning column of 100 drums at the tipping point",
    what = "models.stack of 100 drums 1 x 0.1 m, each offset 0.01 (1 + d) m (b / n: the joint above drum 1 is the limit); falls for d > 0",
    falls = 1,
    build = function(delta, scale)
      return models.stack{ blocks = TOWER, size = { scale, scale, 0.1 * scale }, offset = scale * (1 + delta) / TOWER }
    end,
    boxes = function(delta)
      local boxes = {}
      for k = 1, TOWER do boxes[k] = { x = (k - 1) * (1 + delta) / TOWER, b = 1, h = 0.1 } end
      return boxes
    end,
    options = {},
  },
  {
    key = "needle",
    name = "Needle 1:1000, top half at its edge",
    what = "two 0.001 x 0.5 m blades, the top one offset b/2 (1 + d); falls for d > 0",
    falls = 1,
    boxes = function(delta)
      return { { x = 0, b = 1e-3, h = 0.5 }, { x = 0.5e-3 * (1 + delta), b = 1e-3, h = 0.5 } }
    end,
    depth = 0.5,
    options = {},
  },
  {
    key = "arch",
    name = "Arch at its minimum thickness",
    what = "models.arch R 5 m, 24 voussoirs, no sliding, thickness t* (1 + d), t* by the thrust line; falls for d < 0",
    falls = -1,
    build = function(delta, scale)
      local t = M.arch_threshold(5, ARCH_N)
      return models.arch{ radius = 5 * scale, thickness = t * (1 + delta) * scale, voussoirs = ARCH_N }
    end,
    expect = function(delta)
      -- Symmetric: a lateral load that helps one way helps the other, so
      -- below t* no multiple stands, and above it the factor is positive.
      -- Near t* the factor grows by about 0.41 g per unit of relative
      -- thickness (the secant row checks load_factor's root against the
      -- thrust line): the distance from the edge in g.
      local margin = 0.4 * math.abs(delta)
      if delta == 0 then return { factor = 0, demand = "finite" } end
      if delta < 0 then return { stands = false, factor = "infeasible", demand = "unstable", margin = margin } end
      return { stands = true, factor = "positive", demand = "finite", margin = margin }
    end,
    options = { friction = NO_SLIDING },
  },
  {
    key = "incline",
    name = "Block on an incline at the friction angle",
    what = "slope 0.3 rad, friction tan(0.3) (1 + d); slides for d < 0",
    falls = -1,
    build = function(delta, scale) return incline(INCLINE, scale) end,
    friction = function(delta) return math.tan(INCLINE) * (1 + delta) end,
    expect = function(delta)
      local mu = math.tan(INCLINE) * (1 + delta)
      -- The demand does not depend on delta: it is checked at the edge too.
      if delta == 0 then return { factor = 0, demand = math.tan(INCLINE), demand_exact = true } end
      return { stands = delta > 0, factor = M.incline_factor(INCLINE, mu), demand = math.tan(INCLINE),
               demand_exact = true }
    end,
    options = {},
  },
  {
    key = "pedestal",
    name = "Block balanced on a 1 mm pedestal",
    what = "3D block 1 x 1 x 0.5 m on a 1 x 1 mm support (contact 1e-6 of its face), centroid past the pedestal's edge by d 0.5 mm; falls for d > 0",
    falls = 1,
    build = function(delta, scale)
      local p = 1e-3
      local s = ashlar.structure()
      s:add(ashlar.box{ size = { p * scale, p * scale, 0.5 * scale }, center = { 0, 0, -0.25 * scale } },
            { support = true, name = "pedestal" })
      s:add(ashlar.box{ size = { scale, scale, 0.5 * scale }, center = { p / 2 * (1 + delta) * scale, 0, 0.25 * scale } },
            { name = "block" })
      return s
    end,
    expect = function(delta)
      if delta == 0 then return { factor = 0, demand = 0 } end
      return { stands = delta < 0, factor = -delta * 0.5e-3 / 0.25, demand = delta < 0 and 0 or "unstable" }
    end,
    options = {},
  },
  {
    key = "tilt_tipping",
    name = "Tilt table at the tipping angle",
    what = "ashlar.tilt of a 0.4 x 1.2 m block (depth 0.3) on a ground slab by atan(1/3) (1 + d), no sliding; tips for d > 0",
    falls = 1,
    build = function(delta, scale)
      local s = stack_of({ { x = 0, b = 0.4, h = 1.2 } }, scale, 0.3)
      return ashlar.tilt(s, math.atan(0.4 / 1.2) * (1 + delta))
    end,
    expect = function(delta)
      -- Tilted by theta, gravity leans by theta in the block's frame: it
      -- tips when the resultant leaves the base, tan(atan(b/h) - theta).
      local theta = math.atan(0.4 / 1.2) * (1 + delta)
      local factor = math.tan(math.atan(0.4 / 1.2) - theta)
      if delta == 0 then return { factor = 0, demand = math.tan(theta) } end
      return { stands = delta < 0, factor = factor, demand = delta < 0 and math.tan(theta) or "unstable" }
    end,
    options = { friction = NO_SLIDING },
  },
  {
    key = "tilt_sliding",
    name = "Tilt table at the friction angle",
    what = "ashlar.tilt of a 1 x 0.2 m block (depth 0.6) on a ground slab by atan(0.3) (1 + d), friction 0.3; slides for d > 0",
    falls = 1,
    build = function(delta, scale)
      local s = stack_of({ { x = 0, b = 1, h = 0.2 } }, scale, 0.6)
      return ashlar.tilt(s, math.atan(0.3) * (1 + delta))
    end,
    expect = function(delta)
      local theta = math.atan(0.3) * (1 + delta)
      local factor = math.tan(math.atan(0.3) - theta)
      if delta == 0 then return { factor = 0, demand = math.tan(theta), demand_exact = true } end
      return { stands = delta < 0, factor = factor, demand = math.tan(theta), demand_exact = true }
    end,
    options = { friction = 0.3 },
  },
}

-- Defaults shared by the stack-like families (closed form from boxes).
for _, family in ipairs(M.families) do
  if family.boxes then
    family.build = family.build or function(delta, scale) return stack_of(family.boxes(delta), scale, family.depth) end
    family.expect = family.expect or function(delta)
      local friction = family.options.friction or 0.7
      local factor = stack_expected_factor(family.boxes(delta), friction)
      if delta == 0 then return { factor = 0, demand = 0 } end
      local stands = delta * family.falls < 0
      return { stands = stands, factor = factor, demand = stands and 0 or "unstable" }
    end
  end
end

M.family = {}
for _, family in ipairs(M.families) do M.family[family.key] = family end

-- The options of one method for a family's case at delta.
local function family_options(family, delta, method)
  local options = {}
  for key, value in pairs(family.options) do options[key] = value end
  if family.friction then options.friction = family.friction(delta) end
  if method == "friction_demand" then options.friction = nil end
  return options
end

------------------------------------------------------------------------
-- Judging one method's answer
------------------------------------------------------------------------

local EXPLICIT = { stopped = true, ["numerical difficulties"] = true }

local function factor_tolerance(reference)
  return M.tolerance.factor + M.tolerance.factor_relative * math.abs(reference)
end

-- How far a case is from its edge, in g of lateral acceleration: the
-- reference load factor's size, or the family's own `margin`.
local function margin_of(expect)
  if expect.margin then return expect.margin end
  if type(expect.factor) == "number" then return math.abs(expect.factor) end
  return nil
end

-- Whether either verdict passes: exactly at the edge, or closer to it than
-- the load factor's tolerance (1e-7 g: e.g. a needle 1 mm wide whose top
-- overhangs by 1e-6 of its half width, 5e-10 m).
local function at_edge(expect)
  if expect.stands == nil then return true end
  local margin = margin_of(expect)
  return margin ~= nil and margin <= M.tolerance.factor
end

-- ok (true / false), confident (false when the method said it could not
-- tell), cell text.
local function judge_analyze(r, expect)
  local text = ("%s, %s%s"):format(r.stable and "stable" or "unstable", r.status, r.borderline and ", borderline" or "")
  if expect.floating then
    local ok = not r.stable and #r.floating > 0
    return ok, true, ok and text .. ", floating" or text
  end
  if r.stable == expect.stands then return true, not r.borderline, text end
  if at_edge(expect) then return true, true, text end
  -- Wrong, but does it say so?
  if r.borderline then return true, false, text end
  if not r.stable and r.status ~= "converged" then return true, false, text end
  return false, true, text .. " WRONG"
end

local function judge_load_factor(f, expect)
  local text = f.status == "optimal" and ("%s (%s)"):format(g(f.factor), f.stable and "stands" or "falls")
    or f.status
  if expect.floating then return f.status == "floating", true, text end
  if EXPLICIT[f.status] then return true, false, text end
  local reference = expect.factor
  if reference == nil then return true, true, text end
  local edge = at_edge(expect)
  local near_zero = f.status == "optimal" and math.abs(f.factor) <= M.tolerance.factor
  if reference == "infeasible" then
    -- Within its tolerance of the edge an optimum at about 0 is as good.
    local ok = f.status == "infeasible" or (near_zero and (edge or not f.stable))
    return ok, true, ok and text or text .. " WRONG (infeasible)"
  end
  if reference == "positive" then
    local ok = (f.status == "optimal" and f.factor > -M.tolerance.factor and (edge or f.stable))
      or (edge and f.status == "infeasible")
    return ok, true, ok and text or text .. " WRONG (> 0)"
  end
  if edge and f.status == "infeasible" and math.abs(reference) <= M.tolerance.factor then
    return true, true, text  -- at the edge: no multiple, or only about 0
  end
  if f.status ~= "optimal" then return false, true, ("%s WRONG (%s)"):format(text, g(reference)) end
  local ok = math.abs(f.factor - reference) <= factor_tolerance(reference)
  -- The verdict too, unless the reference is within tolerance of 0.
  if not edge and math.abs(reference) > factor_tolerance(reference) then
    ok = ok and f.stable == expect.stands
  end
  return ok, true, ok and text or ("%s WRONG (%s)"):format(text, g(reference))
end

local function judge_friction_demand(d, expect)
  local text = d.status == "optimal" and g(d.friction) or d.status
  if expect.floating then return d.status == "floating", true, text end
  if EXPLICIT[d.status] then return true, false, text end
  local reference = expect.demand
  if reference == nil then return true, true, text end
  local function value_ok(value)
    if value == "finite" then return d.status == "optimal" and d.friction < math.huge end
    if value == "unstable" then return d.status == "unstable" end
    if d.status ~= "optimal" then return false end
    if value == 0 then return d.friction == 0 end
    return math.abs(d.friction - value) <= M.tolerance.demand_relative * value
  end
  local ok = value_ok(reference)
  if not ok and at_edge(expect) and not expect.demand_exact then
    -- Whether it stands at all is within tolerance: any demand, or none.
    ok = value_ok("unstable") or value_ok("finite")
  end
  local shown = type(reference) == "number" and g(reference) or reference
  return ok, true, ok and text or ("%s WRONG (%s)"):format(text, shown)
end

local function expected_text(expect)
  if expect.floating then return "floating (no contact)" end
  local verdict = expect.stands == nil and "at the edge" or (expect.stands and "stands" or "falls")
  if expect.stands ~= nil and at_edge(expect) then
    verdict = ("%s, within %.0e g of the edge"):format(verdict, margin_of(expect))
  end
  local parts = { verdict }
  if expect.factor ~= nil then
    parts[#parts + 1] = "factor " .. (type(expect.factor) == "number" and g(expect.factor) or expect.factor)
  end
  if expect.demand ~= nil then
    parts[#parts + 1] = "demand " .. (type(expect.demand) == "number" and g(expect.demand) or expect.demand)
  end
  return table.concat(parts, "; ")
end

-- Runs the three methods on s; `options` per method (false: skip it).
-- Returns a row: { name, expected, cells = {analyze, load_factor,
-- friction_demand}, ok = {...}, confident = {...}, values = {...}, pass }.
function M.probe(name, s, expect, options)
  local row = { name = name, expected = expected_text(expect), cells = {}, ok = {}, confident = {}, values = {} }
  local start = os.clock()
  if options.analyze ~= false then
    local r = ashlar.analyze(s, options.analyze or {})
    row.ok.analyze, row.confident.analyze, row.cells.analyze = judge_analyze(r, expect)
    row.values.analyze = { stable = r.stable, status = r.status, borderline = r.borderline }
  end
  if options.load_factor ~= false then
    local f = ashlar.load_factor(s, options.load_factor or {})
    row.ok.load_factor, row.confident.load_factor, row.cells.load_factor = judge_load_factor(f, expect)
    row.values.load_factor = { factor = f.factor, status = f.status, stable = f.stable }
  end
  if options.friction_demand ~= false then
    local d = ashlar.friction_demand(s, options.friction_demand or {})
    row.ok.friction_demand, row.confident.friction_demand, row.cells.friction_demand = judge_friction_demand(d, expect)
    row.values.friction_demand = { friction = d.friction, status = d.status }
  end
  row.pass = true
  for _, ok in pairs(row.ok) do row.pass = row.pass and ok end
  row.seconds = os.clock() - start
  return row
end

-- One family's case at delta (and scale).
function M.family_row(family, delta, scale)
  scale = scale or 1
  local name = ("%s, d = %s%s"):format(family.name, delta == 0 and "0" or ("%+g"):format(delta), scaled_text(scale))
  return M.probe(name, family.build(delta, scale), family.expect(delta), {
    analyze = family_options(family, delta, "analyze"),
    load_factor = family_options(family, delta, "load_factor"),
    friction_demand = family_options(family, delta, "friction_demand"),
  })
end

------------------------------------------------------------------------
-- Single cases
------------------------------------------------------------------------

-- A 1 x 0.5 m block (depth 0.6) on a 2 m ground, turned by -eps about its
-- bottom left edge: its right end lifts eps m. Ground first, so the contact
-- lies in the ground's plane.
local function tilted_block(eps)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 2, 1.2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true, name = "ground" })
  s:add(ashlar.box{ size = { 1, 0.6, 0.5 }, center = { 0, 0, 0.25 } }:rotated({ 0, 1, 0 }, -eps, { -0.5, 0, 0 }),
        { name = "block" })
  s:set_planar(true)
  return s
end

-- Its tipping factor with no sliding: about the contact's right end
-- (-0.5 + cos eps), the centroid turned about (-0.5, 0).
local function tilted_factor(eps)
  local x = -0.5 + 0.5 * math.cos(eps) - 0.25 * math.sin(eps)
  local z = 0.5 * math.sin(eps) + 0.25 * math.cos(eps)
  return (-0.5 + math.cos(eps) - x) / z
end

-- The default contact tolerance of a structure: 1e-6 of its bounding box's
-- diagonal.
local function default_tolerance(s)
  local lo, hi = s:bounds()
  return 1e-6 * math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
end

-- The block raised by `gap` m above the ground.
local function raised_block(gap)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 2, 1.2, 0.5 }, center = { 0, 0, -0.25 } }, { support = true, name = "ground" })
  s:add(ashlar.box{ size = { 1, 0.6, 0.5 }, center = { 0, 0, 0.25 + gap } }, { name = "block" })
  s:set_planar(true)
  return s
end

local single = {}
M.single = single

local function add_single(group, name, build, expect, options)
  single[#single + 1] = { group = group, name = name, build = build, expect = expect, options = options or {} }
end

-- Nearly coplanar contacts.
do
  local group = "Nearly coplanar contacts"
  for _, eps in ipairs{ 1e-9, 1e-7, 1e-6, 1e-5 } do
    local s = tilted_block(eps)
    local touching = eps * 1 <= default_tolerance(s)
    local expect = touching and { stands = true, factor = tilted_factor(eps), demand = 0 } or { floating = true }
    add_single(group, ("Block tilted by %g rad on the ground (lifts %g m; tolerance %.3g m)"):format(eps, eps, default_tolerance(s)),
      function() return tilted_block(eps) end, expect,
      { load_factor = { friction = NO_SLIDING } })
  end
  for _, share in ipairs{ 0.5, 0.99, 1.01, 2 } do
    local tol = default_tolerance(raised_block(0))
    -- The raised block's bounding box grows by the gap: solve for it.
    local gap = share * tol
    for _ = 1, 3 do gap = share * default_tolerance(raised_block(gap)) end
    -- Tipping about the contact (in the ground's plane) with the centroid
    -- 0.25 + gap above it.
    add_single(group, ("Block raised %g x the default contact tolerance"):format(share),
      function() return raised_block(gap) end,
      share < 1 and { stands = true, factor = 0.5 / (0.25 + gap), demand = 0 } or { floating = true },
      { load_factor = { friction = NO_SLIDING } })
  end
  for _, share in ipairs{ 0.5, 2 } do
    local options = { contact_tolerance = 1e-3 }
    add_single(group, ("Block raised %g x contact_tolerance = 1e-3"):format(share),
      function() return raised_block(share * 1e-3) end,
      share < 1 and { stands = true, factor = 0.5 / (0.25 + share * 1e-3), demand = 0 } or { floating = true },
      { analyze = options, load_factor = { contact_tolerance = 1e-3, friction = NO_SLIDING },
        friction_demand = options })
  end
end

-- The incline with other friction cones: an 8-sided pyramid and the box
-- both have an edge along the slip (the contact's u axis), so the same
-- answers.
do
  local group = "Incline with other friction cones"
  for _, cone in ipairs{ { friction_sides = 8 }, { friction_model = "box" } } do
    for _, delta in ipairs{ -1e-4, 1e-4 } do
      local mu = math.tan(INCLINE) * (1 + delta)
      local function with(extra)
        local options = { friction = mu }
        for key, value in pairs(cone) do options[key] = value end
        for key, value in pairs(extra or {}) do options[key] = value end
        return options
      end
      local demand_options = with()
      demand_options.friction = nil
      add_single(group, ("Incline, %s, friction tan(0.3) (1 %s 1e-4)"):format(
          cone.friction_model and "box model" or "8-sided pyramid", delta < 0 and "-" or "+"),
        function() return incline(INCLINE, 1) end,
        { stands = delta > 0, factor = M.incline_factor(INCLINE, mu), demand = math.tan(INCLINE), demand_exact = true },
        { analyze = with(), load_factor = with(), friction_demand = demand_options })
    end
  end
end

-- Blocks that barely touch.
do
  local group = "Blocks that barely touch"
  add_single(group, "3D block centred on a 1 x 1 mm pedestal (contact 1e-6 of its face)",
    function() return M.family.pedestal.build(-1, 1) end,
    { stands = true, factor = 0.5e-3 / 0.25, demand = 0 })
  add_single(group, "3D block on another by a 1 x 1 mm corner (contact 1e-6 of its face)",
    function()
      local s = ashlar.structure()
      s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, -0.25 } }, { support = true, name = "base" })
      s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 1 - 1e-3, 1 - 1e-3, 0.25 } }, { name = "block" })
      return s
    end,
    { stands = false, factor = "infeasible", demand = "unstable" })
  add_single(group, "Block on another by a strip 1e-6 of its width (narrower than the tolerance: no contact)",
    function() return stack_of({ { x = 0, b = 1, h = 0.5 }, { x = 1 - 1e-6, b = 1, h = 0.5 } }) end,
    { floating = true })
  add_single(group, "Block on another by a strip 1e-3 of its width",
    function() return stack_of({ { x = 0, b = 1, h = 0.5 }, { x = 1 - 1e-3, b = 1, h = 0.5 } }) end,
    { stands = false, factor = stack_expected_factor({ { x = 0, b = 1, h = 0.5 }, { x = 1 - 1e-3, b = 1, h = 0.5 } }, 0.7),
      demand = "unstable" })
end

-- Extreme aspect ratios.
do
  local group = "Extreme aspect ratios"
  local slab = { { x = 0, b = 1, h = 1e-3 } }
  add_single(group, "Slab 1000:1 (1 x 0.001 m) lying flat, friction 0.7",
    function() return stack_of(slab, 1, 0.5) end,
    { stands = true, factor = stack_expected_factor(slab, 0.7), demand = 0 })
  add_single(group, "Slab 1000:1 lying flat, no sliding",
    function() return stack_of(slab, 1, 0.5) end,
    { stands = true, factor = stack_expected_factor(slab, NO_SLIDING), demand = 0 },
    { analyze = { friction = NO_SLIDING }, load_factor = { friction = NO_SLIDING } })
  local needle = { { x = 0, b = 1e-3, h = 1 } }
  add_single(group, "Needle 1:1000 (0.001 x 1 m) standing",
    function() return stack_of(needle, 1, 0.5) end,
    { stands = true, factor = stack_expected_factor(needle, 0.7), demand = 0 })
  local drums = {}
  for k = 1, 100 do drums[k] = { x = 0, b = 0.5, h = 0.2 } end
  add_single(group, "Column of 100 drums 0.5 x 0.2 m (models.column, 20 m)",
    function() return models.column{ height = 20, width = 0.5, depth = 0.5, drums = 100 } end,
    { stands = true, factor = stack_expected_factor(drums, 0.7), demand = 0 })
  local function lintel()
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 0.5, 2 }, center = { -4.5, 0, -1 } }, { support = true, name = "post left" })
    s:add(ashlar.box{ size = { 1, 0.5, 2 }, center = { 4.5, 0, -1 } }, { support = true, name = "post right" })
    s:add(ashlar.box{ size = { 10, 0.5, 0.01 }, center = { 0, 0, 0.005 } }, { name = "lintel" })
    s:set_planar(true)
    return s
  end
  add_single(group, "Lintel 1000:1 (10 x 0.01 m) on two posts, friction 0.7",
    lintel, { stands = true, factor = 0.7, demand = 0 })
  add_single(group, "Lintel 1000:1 on two posts, no sliding (tips about the far edge: 5 / 0.005)",
    lintel, { stands = true, factor = 5 / 0.005, demand = 0 },
    { analyze = { friction = NO_SLIDING }, load_factor = { friction = NO_SLIDING } })
end

------------------------------------------------------------------------
-- The cases, in order: families at every delta, singles, scale cases
------------------------------------------------------------------------

M.scales = { 1e-3, 1e3 }
M.scale_deltas = { -1e-6, 1e-6, -1e-4, 1e-4 }
M.scale_families = { "stack", "arch", "incline", "pedestal" }

-- Every case as { group, name, run = function() return row end, scale_group }.
function M.cases()
  local cases = {}
  for _, family in ipairs(M.families) do
    for _, delta in ipairs(M.deltas) do
      cases[#cases + 1] = { group = family.name, family = family, delta = delta, scale = 1,
                            scale_group = family.key .. ("/%g"):format(delta) }
    end
  end
  for _, case in ipairs(single) do cases[#cases + 1] = case end
  for _, key in ipairs(M.scale_families) do
    for _, scale in ipairs(M.scales) do
      for _, delta in ipairs(M.scale_deltas) do
        cases[#cases + 1] = { group = "Scale 1e-3 and 1e3", family = M.family[key], delta = delta, scale = scale,
                              scale_group = key .. ("/%g"):format(delta) }
      end
    end
  end
  for _, case in ipairs(cases) do
    case.name = case.name or ("%s, d = %s%s"):format(case.family.name,
      case.delta == 0 and "0" or ("%+g"):format(case.delta), scaled_text(case.scale))
  end
  return cases
end

-- Runs a case once (memoised on the case table).
function M.run(case)
  if not case.row then
    if case.family then
      case.row = M.family_row(case.family, case.delta, case.scale)
    else
      case.row = M.probe(case.name, case.build(), case.expect, case.options)
    end
  end
  return case.row
end

------------------------------------------------------------------------
-- Checks across cases: thresholds, scale invariance, fine arches, a dome
------------------------------------------------------------------------

-- A row that is not one structure: cells filled by `check`.
local function check_row(name, expected, cells, ok)
  local row = { name = name, expected = expected, cells = cells, ok = ok, confident = {}, values = {} }
  row.pass = true
  for _, value in pairs(ok) do row.pass = row.pass and value end
  return row
end

-- The arch's threshold three ways: the thrust line (reference), the root of
-- load_factor's factor in t by the secant method to 1e-12 (from above, where
-- it is defined), and bisection of analyze's verdict to 1e-10.
function M.arch_thresholds(N, scale)
  scale = scale or 1
  local reference = M.arch_threshold(5, N)
  local function factor(t)
    local f = ashlar.load_factor(models.arch{ radius = 5 * scale, thickness = t * scale, voussoirs = N },
                                 { friction = NO_SLIDING })
    return f.status == "optimal" and f.factor or nil, f
  end
  -- Secant from t*(1 + 1e-2) and t*(1 + 1e-3); a step below the root (no
  -- factor there) is halved back towards the last point above.
  local t0, t1 = reference * (1 + 1e-2), reference * (1 + 1e-3)
  local f0, f1 = factor(t0), factor(t1)
  local secant = nil
  if f0 and f1 then
    for _ = 1, 60 do
      local t2 = t1 - f1 * (t1 - t0) / (f1 - f0)
      local f2 = factor(t2)
      while not f2 and t2 < t1 do
        t2 = (t2 + t1) / 2
        f2 = factor(t2)
      end
      if not f2 then break end
      t0, f0, t1, f1 = t1, f1, t2, f2
      if math.abs(t1 - t0) <= 1e-12 * t1 or f1 == f0 then break end
    end
    secant = t1
  end
  local function stands(t)
    return ashlar.analyze(models.arch{ radius = 5 * scale, thickness = t * scale, voussoirs = N },
                          { friction = NO_SLIDING }).stable
  end
  local lo, hi = reference * 0.99, reference * 1.01
  local bisected = nil
  if not stands(lo) and stands(hi) then
    while hi - lo > 1e-10 * hi do
      local middle = (lo + hi) / 2
      if stands(middle) then hi = middle else lo = middle end
    end
    bisected = (lo + hi) / 2
  end
  return reference, secant, bisected
end

-- Relative difference, or math.huge when either is missing.
local function relative(a, b)
  if not a or not b then return math.huge end
  return math.abs(a - b) / math.abs(b)
end

function M.threshold_row(N, scale)
  local reference, secant, bisected = M.arch_thresholds(N, scale)
  local secant_error, bisected_error = relative(secant, reference), relative(bisected, reference)
  return check_row(("Arch threshold, %d voussoirs%s: t*/R by three methods"):format(N, scaled_text(scale or 1)),
    ("thrust line t*/R = %.12f"):format(reference / 5),
    { analyze = ("bisection %.12f (%.1e)"):format((bisected or 0) / 5, bisected_error),
      load_factor = ("secant root %.12f (%.1e)"):format((secant or 0) / 5, secant_error),
      friction_demand = "–" },
    -- The analysis resolves the edge to its stable_tolerance; the LP to
    -- rounding.
    { analyze = bisected_error <= 1e-6, load_factor = secant_error <= 1e-9 })
end

-- The arch's minimum thickness by ashlar.geometric_factor (bisection of
-- analyze's verdict to 1e-9) at three scales, against the thrust line.
function M.geometric_factor_row()
  local reference = M.arch_threshold(5, ARCH_N)
  local cells, worst, spread, ratios = {}, 0, 0, {}
  for _, scale in ipairs{ 1e-3, 1, 1e3 } do
    local found = ashlar.geometric_factor(function(t)
      return models.arch{ radius = 5 * scale, thickness = t, voussoirs = ARCH_N }
    end, 0.6 * scale, { friction = NO_SLIDING, tolerance = 1e-9 })
    local ratio = found.status == "converged" and found.minimum / (5 * scale) or math.huge
    ratios[#ratios + 1] = ratio
    worst = math.max(worst, relative(ratio, reference / 5))
    spread = math.max(spread, relative(ratio, ratios[1]))
  end
  cells.analyze = ("t*/R %.10f, %.10f, %.10f: %.1e from the thrust line, spread %.1e"):format(
    ratios[1], ratios[2], ratios[3], worst, spread)
  cells.load_factor, cells.friction_demand = "–", "–"
  return check_row("Arch minimum thickness by ashlar.geometric_factor at scales 1e-3, 1, 1e3",
    ("thrust line t*/R = %.10f"):format(reference / 5), cells,
    { analyze = worst <= 1e-6 and spread <= M.tolerance.scale_relative })
end

-- A fine arch against Heyman's and Milankovitch's t/R = 0.1075: the
-- thrust line at 512 voussoirs, and analyze at 128 on either side of the
-- thrust line's threshold for 128 by 1e-4.
function M.heyman_row()
  local fine = M.arch_threshold(5, 512) / 5
  local t = M.arch_threshold(5, 128)
  local above = ashlar.analyze(models.arch{ radius = 5, thickness = t * (1 + 1e-4), voussoirs = 128 },
                               { friction = NO_SLIDING })
  local below = ashlar.analyze(models.arch{ radius = 5, thickness = t * (1 - 1e-4), voussoirs = 128 },
                               { friction = NO_SLIDING })
  local heyman_ok = math.abs(fine - 0.1075) <= 5e-5  -- 0.1075 is given to four digits
  return check_row("Fine arch: minimum t/R against Heyman's 0.1075",
    ("0.1075; thrust line %.6f at 512 voussoirs"):format(fine),
    { analyze = ("128 voussoirs, t*(1 -/+ 1e-4): %s / %s"):format(below.stable and "stable" or "unstable",
                                                                 above.stable and "stable" or "unstable"),
      load_factor = "–", friction_demand = "–" },
    { analyze = heyman_ok and above.stable and not below.stable })
end

-- The arch's minimum thickness by bisection of analyze at three scales:
-- the ratios t*/R must agree.
function M.scale_threshold_row()
  local ratios, cells, worst = {}, {}, 0
  for _, scale in ipairs{ 1e-3, 1, 1e3 } do
    local _, _, bisected = M.arch_thresholds(ARCH_N, scale)
    ratios[#ratios + 1] = bisected and bisected / 5 or math.huge
  end
  for k = 2, #ratios do worst = math.max(worst, relative(ratios[k], ratios[1])) end
  cells.analyze = ("t*/R %.10f, %.10f, %.10f (spread %.1e)"):format(ratios[1], ratios[2], ratios[3], worst)
  cells.load_factor, cells.friction_demand = "–", "–"
  return check_row("Arch minimum thickness by analyze at scales 1e-3, 1, 1e3", "equal t*/R",
                   cells, { analyze = worst <= M.tolerance.scale_relative })
end

-- A dome (8 meridians x 6 parallels, friction 0.7) at three scales: at
-- t/R = 0.1 it stands (minimum about 0.045), at 0.03 it does not; the
-- answers agree across scales.
function M.dome_rows()
  local rows = {}
  for _, ratio in ipairs{ 0.1, 0.03 } do
    local per_scale = {}
    for _, scale in ipairs{ 1e-3, 1, 1e3 } do
      local s = models.dome{ radius = 5 * scale, thickness = ratio * 5 * scale, meridians = 8, parallels = 6 }
      local stands = ratio > 0.05
      per_scale[#per_scale + 1] = M.probe(("Dome 8 x 6, t/R = %g%s"):format(ratio, scaled_text(scale)), s,
        { stands = stands, factor = not stands and "infeasible" or nil, demand = not stands and "unstable" or nil },
        { friction_demand = ratio > 0.05 and scale == 1 and {} or (ratio < 0.05 and {} or false) })
      rows[#rows + 1] = per_scale[#per_scale]
    end
    rows[#rows + 1] = M.compare_scales(("Dome 8 x 6, t/R = %g: scales 1e-3, 1, 1e3 agree"):format(ratio), per_scale)
  end
  return rows
end

-- Whether rows of one model at several scales agree: the same verdicts,
-- load factors and friction demands equal to scale_relative.
function M.compare_scales(name, rows)
  local cells, ok = {}, {}
  local function spread(method, field)
    local worst, first = 0, nil
    for _, row in ipairs(rows) do
      local v = row.values[method]
      if v and type(v[field]) == "number" and v[field] == v[field] and math.abs(v[field]) < math.huge then
        if first == nil then first = v[field] end
        worst = math.max(worst, math.abs(v[field] - first) / math.max(math.abs(first), 1e-3))
      end
    end
    return worst
  end
  local function same(method, fields)
    local first = nil
    for _, row in ipairs(rows) do
      local v = row.values[method]
      if v then
        local key = {}
        for _, field in ipairs(fields) do key[#key + 1] = tostring(v[field]) end
        key = table.concat(key, "/")
        if first == nil then first = key elseif key ~= first then return false end
      end
    end
    return true
  end
  local analyze_same = same("analyze", { "stable" })
  cells.analyze = analyze_same and "same verdicts" or "verdicts DIFFER"
  ok.analyze = analyze_same
  local factor_spread = spread("load_factor", "factor")
  local factor_same = same("load_factor", { "status", "stable" })
  cells.load_factor = ("%s, factors within %.1e"):format(factor_same and "same status" or "status DIFFERS", factor_spread)
  ok.load_factor = factor_same and factor_spread <= M.tolerance.scale_relative
  local demand_spread = spread("friction_demand", "friction")
  local demand_same = same("friction_demand", { "status" })
  cells.friction_demand = ("%s, within %.1e"):format(demand_same and "same status" or "status DIFFERS", demand_spread)
  ok.friction_demand = demand_same and demand_spread <= M.tolerance.demand_relative
  return check_row(name, "the same answers", cells, ok)
end

-- The scale groups of a list of cases (after M.run), compared.
function M.scale_rows(cases)
  local groups, order = {}, {}
  for _, case in ipairs(cases) do
    if case.scale and case.scale ~= 1 then
      local key = case.scale_group
      if not groups[key] then groups[key] = {}; order[#order + 1] = key end
    end
  end
  for _, case in ipairs(cases) do
    if groups[case.scale_group] then table.insert(groups[case.scale_group], M.run(case)) end
  end
  local rows = {}
  for _, key in ipairs(order) do
    local family, delta = key:match("^(%w+)/(.*)$")
    rows[#rows + 1] = M.compare_scales(("%s, d = %+g: scales 1e-3, 1, 1e3 agree"):format(M.family[family].name,
                                                                                      tonumber(delta)), groups[key])
  end
  return rows
end

------------------------------------------------------------------------
-- How close to the edge each method stays right
------------------------------------------------------------------------

-- Whether a method's answer in row (of a family's case at delta) says
-- that the structure stands.
local function says_stands(family, delta, row, method)
  local v = row.values[method]
  if method == "analyze" then return v.stable end
  if method == "load_factor" then return (v.status == "optimal" or v.status == "unbounded") and v.stable end
  local friction = family_options(family, delta, "load_factor").friction or 0.7
  return v.status == "optimal" and v.friction <= friction
end

M.methods = { "analyze", "load_factor", "friction_demand" }

-- For each method, over delta = 1e-1 .. 1e-10 on both sides of the edge:
-- `right`, the smallest delta down to which its verdict (analyze: stable;
-- load_factor: stable; friction_demand: a demand no larger than the
-- friction used) is right on both sides, at that delta and every larger
-- one; `passes`, down to which every answer passes the checks (right,
-- within its tolerance, or flagged); `wrong`, the largest delta at which an
-- answer fails them (nil: none).
function M.resolution(family)
  local result = {}
  for _, method in ipairs(M.methods) do result[method] = {} end
  for k = 1, 10 do
    local delta = 10 ^ -k
    local rows = { M.family_row(family, delta, 1), M.family_row(family, -delta, 1) }
    for _, method in ipairs(M.methods) do
      local entry = result[method]
      local right, passes = true, true
      for i, sign in ipairs{ 1, -1 } do
        local stands = sign * family.falls < 0
        right = right and says_stands(family, sign * delta, rows[i], method) == stands
        passes = passes and rows[i].ok[method]
      end
      if right and not entry.right_broken then entry.right = delta else entry.right_broken = true end
      if passes and not entry.passes_broken then entry.passes = delta else entry.passes_broken = true end
      if not passes and not entry.wrong then entry.wrong = delta end
    end
  end
  return result
end

------------------------------------------------------------------------
-- The markdown table
------------------------------------------------------------------------

local function escape(text) return (tostring(text or "–"):gsub("|", "\\|")) end

function M.markdown(rows)
  local lines = { "| case | expected | analyze | load_factor | friction_demand | pass |", "|---|---|---|---|---|---|" }
  local group = nil
  for _, row in ipairs(rows) do
    if row.group and row.group ~= group then
      group = row.group
      lines[#lines + 1] = ("| **%s** | | | | | |"):format(escape(group))
    end
    lines[#lines + 1] = ("| %s | %s | %s | %s | %s | %s |"):format(escape(row.name), escape(row.expected),
      escape(row.cells.analyze), escape(row.cells.load_factor), escape(row.cells.friction_demand),
      row.pass and "pass" or "**FAIL**")
  end
  return table.concat(lines, "\n") .. "\n"
end

-- A failed row as one line for an assertion message.
function M.describe(row)
  local parts = { row.name, "expected: " .. row.expected }
  for _, method in ipairs(M.methods) do
    if row.cells[method] then
      parts[#parts + 1] = ("%s: %s%s"):format(method, row.cells[method], row.ok[method] == false and " <-- " or "")
    end
  end
  return table.concat(parts, "; ")
end

return M
