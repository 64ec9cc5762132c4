-- Figure 3 of Shin 2014: a cable-stayed bridge (models.cable_stayed_bridge)
-- whose walkway is too heavy for its vertical arch, made stable by moving
-- vertices down the structural gradient (L-BFGS), in the thesis's two cases:
--   (b) the walkway and the cables fixed, only the vertical arch free;
--   (c) everything free but the supports, each walkway block's top face
--       keeping its (horizontal) normal.
--   ashlar scripts/figure3_bridge.lua [output folder, default "docs/figures/bridge"]
-- Writes the bridge before and after each case as .glb (with the contact
-- forces of its analysis), the history of each case as CSV
-- (figure3_bridge_b.csv, figure3_bridge_c.csv), a chart of the penalty per
-- iteration (figure3_bridge.png / .svg), and prints iterations, analyses
-- and time to stable per case, and how the blocks changed.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"

local folder = arg[1] or "docs/figures/bridge"
os.execute("mkdir -p " .. script_support.shell_quoted(folder))

local bridge = models.cable_stayed_bridge{}
local analysis = { friction = 0.7 }

-- The top face of every walkway block: all its vertices at the block's
-- highest z (the generator makes it horizontal).
local function deck_tops(s)
  local tops = {}
  for i = 1, #s do
    if s:name(i):match("^deck %d+$") then
      local block = s:block(i)
      local vertices, _, hi = block:vertices(), block:bounds()
      for f, face in ipairs(block:faces()) do
        local on_top = true
        for _, k in ipairs(face) do on_top = on_top and vertices[k][3] == hi[3] end
        if on_top then tops[#tops + 1] = { block = i, face = f } end
      end
    end
  end
  return tops
end

local common = {
  method = "lbfgs",
  analysis = analysis,
  max_iterations = 50,
  -- The bridge is symmetric about x = 0: mirrored moves keep it so, as in
  -- the thesis's figure (free moves need not), and halve the unknowns.
  symmetry = { point = { 0, 0, 0 }, normal = { 1, 0, 0 } },
}
local function with(options)
  for key, value in pairs(common) do options[key] = value end
  return options
end
local cases = {
  { name = "b", title = "(b) walkway and cables fixed, vertical arch free",
    options = with{ fixed_names = "^deck", fixed_cables = true } },
  { name = "c", title = "(c) walkway tops kept horizontal, cables and both arches free",
    options = with{ keep_normal = deck_tops(bridge) } },
}

local function export(s, name)
  local r = ashlar.analyze(s, analysis)
  ashlar.export(s, ("%s/%s.glb"):format(folder, name), { result = r, forces = true })
  return r
end

-- Total volume of the blocks whose names match `pattern`, and the mean y of
-- their centroids weighted by volume (how far the arch leans off y = 0).
local function volume(s, pattern)
  local total, moment = 0, 0
  for i = 1, #s do
    if s:name(i):match(pattern) then
      local block = s:block(i)
      total = total + block:volume()
      moment = moment + block:volume() * block:centroid()[2]
    end
  end
  return total, moment / total
end

local before = export(bridge, "figure3_bridge_before")
print(("as given: %s, infeasibility %.4f (friction %.1f)"):format(before.stable and "stable" or "unstable",
  before.infeasibility, analysis.friction))
local arch_volume, arch_y = volume(bridge, "^arch voussoir")
local middle_volume = volume(bridge, "^deck [56]$")
local end_volume = volume(bridge, "^deck 1$") + volume(bridge, "^deck 10$")

for _, case in ipairs(cases) do
  local r = ashlar.optimize(bridge, case.options)
  local rows = { "iteration,penalty,infeasibility,step_m,seconds,stable" }
  for _, h in ipairs(r.history) do
    rows[#rows + 1] = ("%d,%.9g,%.9g,%.6g,%.6f,%s"):format(h.iteration, h.penalty, h.infeasibility, h.step,
      h.seconds, tostring(h.stable))
  end
  script_support.write_atomically(("%s/figure3_bridge_%s.csv"):format(folder, case.name),
    table.concat(rows, "\n") .. "\n")
  local after = export(r.structure, "figure3_bridge_" .. case.name .. "_after")
  local last = r.history[#r.history]
  print(("%s: %s (%s) after %d iterations, %d analyses with gradient, %.3f s; re-analysed: %s"):format(
    case.title, r.stable and "stable" or "NOT stable", r.status, last.iteration, r.evaluations, last.seconds,
    after.stable and "stable" or ("unstable, infeasibility %.3g"):format(after.infeasibility)))
  local v, y = volume(r.structure, "^arch voussoir")
  print(("    vertical arch: volume x %.2f, centre of mass at y = %+.3f m (was %+.3f)"):format(v / arch_volume, y,
    arch_y))
  print(("    walkway: mid-span blocks' volume x %.2f, end blocks' x %.2f"):format(
    volume(r.structure, "^deck [56]$") / middle_volume,
    (volume(r.structure, "^deck 1$") + volume(r.structure, "^deck 10$")) / end_volume))
end

local function csv(name) return ("%s/figure3_bridge_%s.csv"):format(folder, name) end
-- The chart from the CSVs: one line per case, named in the legend.
local CASES = { b = "(b) vertical arch free", c = "(c) walkway tops horizontal, all free" }
local points = {}
for _, name in ipairs{ "b", "c" } do
  for _, row in ipairs(script_support.read_csv(csv(name))) do
    points[#points + 1] = { iteration = row.iteration, [CASES[name]] = row.penalty }
  end
end
script_support.chart(folder .. "/figure3_bridge", { data = points, x = "iteration", y = { CASES.b, CASES.c },
  log_y = true, title = "Cable-stayed bridge made stable by L-BFGS (Shin 2014, figure 3; friction 0.7)",
  y_label = "penalty (infeasibility measure)" })
