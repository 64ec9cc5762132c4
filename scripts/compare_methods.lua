-- The two methods side by side (ashlar.analyze's default "equilibrium" and
-- "kinematic"): the truth table of cases where rigid-block equilibrium is
-- known to be wrong or right, with the kinematic mechanism of every falling
-- case; both verdicts for every model of the library at its defaults; the
-- load factor of a running-bond wall by each method; and the time of each
-- method against block count.
--   ashlar scripts/compare_methods.lua [folder for kinematic_scaling.csv and charts (default .)] [--charts]
-- With --charts it only draws the chart again from the folder's CSV.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "script_support"

local charts_only = support.charts_only()
local folder = arg[1] or "."
local here = arg[0]:match("^(.*)/") or "."
local log_chart = dofile(here .. "/log_chart.lua")

-- Time against block count (rows of kinematic_scaling.csv), as
-- kinematic_scaling.png and .svg.
local function draw_scaling(rows)
  log_chart.draw_all({
    title = "Analysis time against block count: equilibrium and kinematic methods",
    ylabel = "seconds (whole analysis)",
    series = {
      { kind = "wall", column = "equilibrium_s", title = "running-bond wall, equilibrium" },
      { kind = "wall", column = "kinematic_s", title = "running-bond wall, kinematic" },
      { kind = "vault", column = "equilibrium_s", title = "barrel vault, equilibrium" },
      { kind = "vault", column = "kinematic_s", title = "barrel vault, kinematic" },
    },
  }, rows, folder .. "/kinematic_scaling")
end

if charts_only then
  draw_scaling(support.read_csv(folder .. "/kinematic_scaling.csv"))
  print("wrote " .. folder .. "/kinematic_scaling.png / .svg")
  return
end
local cases_of = dofile(here .. "/kinematic_cases.lua")
local clamped, wedge, flat_arch, incline, stack = cases_of.clamped, cases_of.wedge, cases_of.flat_arch,
  cases_of.incline, cases_of.stack

-- "falls: block 3 (0, 0, -1); 1-3 sliding, 2-3 sliding": the fastest block's
-- velocity and the interfaces that move.
local function mechanism_text(s, r)
  if not r.mechanism then return "" end
  local fastest, speed = 0, -1
  for i, m in ipairs(r.mechanism) do
    local v = m.velocity
    local length = math.sqrt(v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2)
    if length > speed then fastest, speed = i, length end
  end
  local v = r.mechanism[fastest].velocity
  local joints = {}
  for k, joint in ipairs(r.limit) do
    if k > 4 then joints[#joints + 1] = ("and %d more"):format(#r.limit - 4) break end
    joints[#joints + 1] = ("%d-%d %s"):format(joint.a, joint.b, joint.mode)
  end
  return ("block %d moves (%.2f, %.2f, %.2f); %s"):format(fastest, v[1], v[2], v[3], table.concat(joints, ", "))
end

print("Truth table (friction mu; equilibrium / kinematic verdicts; the kinematic mechanism when it falls)")
print(("%-44s %5s %-12s %-12s %s"):format("case", "mu", "equilibrium", "kinematic", "kinematic mechanism"))
local cases = {
  { "block between two walls, no floor", clamped, { 0.3, 0.9 }, "falls" },
  { "wedge in a V, faces 15 deg from vertical", wedge, { 0, 0.3, 0.9 }, "stands" },
  { "flat arch, 5 voussoirs, vertical joints", function() return flat_arch(nil) end, { 0.3, 0.6, 0.9 }, "falls" },
  { "flat arch, joints converging 1.5 m below", function() return flat_arch(1.5) end, { 0.3, 0.6, 0.9 }, "stands" },
  { "block on an incline, tan theta = mu - 2 deg", nil, { 0.3, 0.6 }, "stands" },
  { "block on an incline, tan theta = mu + 2 deg", nil, { 0.3, 0.6 }, "falls" },
  { "harmonic stack of 2, overhang x 0.98", function() return stack(0.98) end, { 0.6 }, "stands" },
  { "harmonic stack of 2, overhang x 1.02", function() return stack(1.02) end, { 0.6 }, "falls" },
  { "semicircular arch, 16 voussoirs, t/R 0.104", function() return models.arch{ radius = 5, thickness = 0.52, voussoirs = 16 } end,
    { math.huge, 10, 0.7 }, "falls" },
  { "semicircular arch, 16 voussoirs, t/R 0.110", function() return models.arch{ radius = 5, thickness = 0.55, voussoirs = 16 } end,
    { math.huge, 10, 0.7 }, "stands" },
}
local wrong = 0
for _, case in ipairs(cases) do
  for _, mu in ipairs(case[3]) do
    local s = case[2] and case[2]() or incline(math.atan(mu) + math.rad(case[1]:find("%- 2") and -2 or 2))
    local e = ashlar.analyze(s, { friction = mu })
    local k = ashlar.analyze(s, { friction = mu, method = "kinematic" })
    local verdict = k.stable and "stands" or "falls"
    if verdict ~= case[4] then wrong = wrong + 1 end
    print(("%-44s %5s %-12s %-12s %s"):format(case[1], tostring(mu), e.stable and "stands" or "falls",
      verdict .. (verdict == case[4] and "" or " (WRONG)"), k.stable and "" or mechanism_text(s, k)))
  end
end
print(("%d kinematic verdicts against physics wrong"):format(wrong))

print("\nThe model library at its defaults, friction 0.7")
print(("%-22s %6s %-12s %-12s %8s %9s %9s %s"):format("model", "blocks", "equilibrium", "kinematic", "rounds", "eq s", "kin s",
  "borrowed friction (interfaces, N)"))
local names = {}
for name, generator in pairs(models) do
  if type(generator) == "function" and name ~= "perturbed" then names[#names + 1] = name end
end
table.sort(names)
for _, name in ipairs(names) do
  local s = models[name]{}
  local c = ashlar.compare_methods(s, { friction = 0.7, margin = false })
  local borrowed = ""
  if #c.borrowed > 0 then
    local total = 0
    for _, b in ipairs(c.borrowed) do total = total + b.friction - b.available end
    borrowed = ("%d, %.0f"):format(#c.borrowed, total)
  end
  print(("%-22s %6d %-12s %-12s %8d %9.3f %9.3f %s"):format(name, #s, c.equilibrium.stable and "stands" or "falls",
    c.kinematic.stable and "stands" or "falls", c.kinematic.rounds, c.equilibrium.seconds, c.kinematic.seconds, borrowed))
end

print("\nRunning-bond wall (models.wall{}, 3D) under a growing lateral body force: load factor by each method")
do
  local s = models.wall{}
  s:set_planar(false)
  for _, mu in ipairs{ 0.3, 0.6 } do
    local t0 = ashlar.clock()
    local e = ashlar.load_factor(s, { friction = mu, direction = { 1, 0, 0 } })
    local t1 = ashlar.clock()
    local k = ashlar.load_factor(s, { friction = mu, direction = { 1, 0, 0 }, method = "kinematic" })
    print(("%d blocks, mu %.1f: equilibrium %.4f (%.2f s), kinematic %.4f (%s, %d analyses, %.2f s)"):format(#s, mu,
      e.factor, t1 - t0, k.factor, k.status, k.analyses, k.seconds))
  end
end

print("\nTime against block count (friction 0.7; seconds of the whole analysis)")
local rows = { "structure,blocks,equilibrium_s,kinematic_s,rounds,equilibrium_stable,kinematic_stable" }
local chart_rows = {}
print(("%-6s %7s %13s %11s %7s"):format("", "blocks", "equilibrium s", "kinematic s", "rounds"))
local sizes = {
  wall = { 10, 32, 100 },
  vault = { { 24, 6 }, { 25, 40 }, { 50, 200 } },
}
for _, kind in ipairs{ "wall", "vault" } do
  for _, size in ipairs(sizes[kind]) do
    local s
    if kind == "wall" then
      s = models.wall{ length = size * 0.24, height = size * 0.07 }
      s:set_planar(false)
    else
      s = models.barrel_vault{ radius = 2, thickness = 0.4, voussoirs = size[1], courses = size[2], length = size[2] / 4,
                               bond = "running" }
    end
    s:interfaces()
    local e = ashlar.analyze(s, { friction = 0.7 })
    local k = ashlar.analyze(s, { friction = 0.7, method = "kinematic" })
    print(("%-6s %7d %13.2f %11.2f %7d"):format(kind, #s, e.seconds, k.seconds, k.rounds))
    rows[#rows + 1] = ("%s,%d,%.4f,%.4f,%d,%s,%s"):format(kind, #s, e.seconds, k.seconds, k.rounds, tostring(e.stable),
      tostring(k.stable))
    chart_rows[#chart_rows + 1] = { structure = kind, blocks = #s, equilibrium_s = e.seconds, kinematic_s = k.seconds }
  end
end
local csv = folder .. "/kinematic_scaling.csv"
local file = assert(io.open(csv .. ".tmp", "w"))
file:write(table.concat(rows, "\n"), "\n")
file:close()
assert(os.rename(csv .. ".tmp", csv))

draw_scaling(chart_rows)
print("wrote " .. csv .. " and kinematic_scaling.png / .svg")
