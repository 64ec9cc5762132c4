-- The thesis's chapter 5 (Shin 2014, figures 12, 14, 15), remade with the
-- FEA, and the comparison of equilibrium and FEA over arch thickness:
--   ashlar scripts/figures/chapter5.lua [folder] [--charts]    (default docs/figures/chapter5)
-- Writes per figure the FEA's deformed shape (.glb, tension nodes red,
-- released ones orange; a PNG when f3d and xvfb-run are installed), the
-- mesh with every result (.vtu, for ParaView), equilibrium drawings with
-- the thrust line, the dome's hoop-to-meridional chart and the thickness
-- sweep's chart, CSV and table (Markdown, printed). With --charts it only
-- draws the two charts again from the folder's CSVs.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local courses = require "ashlar.models.courses"
package.path = (arg[0]:match("^(.*)/[^/]+/[^/]+$") or "..") .. "/?.lua;" .. package.path
local support = require "script_support"

local charts_only = support.charts_only()
local folder = arg[1] or "docs/figures/chapter5"
support.make_folders(folder)
local pictures = support.can_render()
if not pictures then print("f3d or xvfb-run not found: no PNG renderings of the .glb files") end
local NO_SLIDING = { friction = math.huge }
local FRONT = { azimuth = 0, elevation = 0 }
local ABOVE = { azimuth = 0, elevation = 30 }

local function path(name) return ("%s/%s"):format(folder, name) end

-- The dome's hoop-to-meridional ratio per course, from figure15_hoop_ratio.csv.
local function draw_hoop_ratio()
  local NAMES = { equilibrium = "equilibrium", fea_relaxed = "FEA after relaxation",
                  fea_tied = "FEA, every contact tied (negative: hoop tension)" }
  local points = {}
  for _, row in ipairs(support.read_csv(path("figure15_hoop_ratio.csv"))) do
    local point = { course = row.course }
    for column, name in pairs(NAMES) do point[name] = row[column] end
    points[#points + 1] = point
  end
  support.chart(path("figure15_hoop_ratio"), { data = points, x = "course",
    y = { NAMES.equilibrium, NAMES.fea_relaxed, NAMES.fea_tied }, x_label = "course (1 = bottom)",
    y_label = "mean hoop-joint force / mean bed-joint force",
    title = "Hemispherical dome (R = 5 m, t = 0.5 m, 16 x 8, oculus): hoop / meridional force per course" })
end

-- The thickness sweep's verdicts, from arch_methods.csv: 1 stable
-- (compression-only), 0 unstable (tension remains), -1 a mechanism; the
-- FEA's lines moved by 0.05 so that equal verdicts stay apart.
local function draw_arch_methods()
  local EQUILIBRIUM, ALL, LARGEST = "equilibrium", "FEA, release = all (- 0.05)", "FEA, release = largest (+ 0.05)"
  local points = {}
  for _, row in ipairs(support.read_csv(path("arch_methods.csv"))) do
    points[#points + 1] = { t = row.t_over_R, [EQUILIBRIUM] = row.equilibrium_stable, [ALL] = row.all_status - 0.05,
                            [LARGEST] = row.largest_status + 0.05 }
  end
  support.chart(path("arch_methods"), { data = points, x = "t", y = { EQUILIBRIUM, ALL, LARGEST }, kind = "steps",
    title = "Semicircular arch, 24 voussoirs: equilibrium against FEA with constraint relaxation",
    x_label = "t/R (thickness over centreline radius; Milankovitch's limit 0.1075)",
    y_label = "1: stable / compression-only, 0: unstable / tension, -1: mechanism" })
end

if charts_only then
  draw_hoop_ratio()
  draw_arch_methods()
  print("wrote " .. path("figure15_hoop_ratio.png") .. ", " .. path("arch_methods.png") .. " and their .svg")
  return
end

local function export(fe, name, options, view)
  fe:export(path(name .. ".glb"), options)
  if pictures then support.render(path(name .. ".glb"), view) end
end

local function timed(f, ...)
  local start = ashlar.clock()
  local result = f(...)
  return result, ashlar.clock() - start
end

local function tensile_count(fe)
  local n = 0
  for _, c in ipairs(fe.contacts) do if c.tensile then n = n + 1 end end
  return n
end

local function describe_relaxation(label, fe)
  local steps = {}
  for i, h in ipairs(fe.history) do steps[i] = ("%d tensile (%.0f N)"):format(h.tensile, h.tension) end
  print(("  %s: %s after %d iterations; per solve: %s"):format(label, fe.status, fe.iterations,
    table.concat(steps, ", ")))
end

-- Figure 12 -----------------------------------------------------------------
print("Figure 12: semicircular arch, R = 5 m, t = 0.6 m (t/R = 0.12), 24 voussoirs, one element each")
local arch = models.arch{ radius = 5, thickness = 0.6, voussoirs = 24 }
local r = ashlar.analyze(arch, NO_SLIDING)
print(("  equilibrium (no sliding): stable = %s, infeasibility %.2g"):format(tostring(r.stable), r.infeasibility))
ashlar.draw(arch, path("figure12_equilibrium.svg"), { result = r, thrust = true })
ashlar.draw(arch, path("figure12_equilibrium.png"), { result = r, thrust = true })
local tied = ashlar.fea(arch, { relax = false })
local crown = {}
for _, c in ipairs(tied.contacts) do
  if c.tensile then crown[#crown + 1] = ("(%.2f, %.2f)"):format(c.position[1], c.position[3]) end
end
print(("  FEA, every contact tied: %s; nodes in tension at (x, z) = %s"):format(tied.status, table.concat(crown, " ")))
export(tied, "figure12_fea_tension", { color = "block" }, FRONT)
describe_relaxation("relaxation, the thesis's rule (release = all)", ashlar.fea(arch, { method = "relaxation" }))
local relaxed = ashlar.fea(arch, { method = "relaxation", release = "largest" })
describe_relaxation("relaxation, one interface at a time (release = largest)", relaxed)
describe_relaxation("unilateral contact (the default)", ashlar.fea(arch))
export(relaxed, "figure12_fea_relaxed", { scale = 3000 }, FRONT)
relaxed:export(path("figure12_fea_relaxed.vtu"))

-- Figure 14 -----------------------------------------------------------------
print("Figure 14: lintel on three posts (0.15, 1.0, 0.3 m wide), spans 2.85 and 1.7 m")
local posts = models.post_and_lintel{ posts = { { width = 0.15 }, { width = 1.0 }, { width = 0.3 } },
                                      spans = { 2.85, 1.7 }, lintel = { 6, 0.5, 0.3 } }
print(("  equilibrium: stable = %s"):format(tostring(ashlar.analyze(posts).stable)))
local posts_tied = ashlar.fea(posts, { relax = false })
for _, c in ipairs(posts_tied.contacts) do
  if c.tensile then
    local f = posts_tied.interfaces[c.interface]
    print(("  FEA, tied: tension %.0f N at (%.2f, %.2f, %.2f) between %s and %s"):format(-c.normal_force,
      c.position[1], c.position[2], c.position[3], posts:name(f.a), posts:name(f.b)))
  end
end
export(posts_tied, "figure14_fea_tension", { color = "block" }, FRONT)
local posts_relaxed = ashlar.fea(posts)
describe_relaxation("relaxation", posts_relaxed)
for _, k in ipairs(posts_relaxed.released) do
  local c = posts_relaxed.contacts[k]
  print(("  released node at (%.2f, %.2f, %.2f) opens %.3g m (largest displacement %.3g m)"):format(
    c.position[1], c.position[2], c.position[3], c.opening, posts_relaxed.max_displacement))
end
export(posts_relaxed, "figure14_fea_hinge", { scale = 20000, undeformed = true }, FRONT)
posts_relaxed:export(path("figure14_fea_hinge.vtu"))
for _, size in ipairs{ 0.15, 0.1 } do
  local fine = ashlar.fea(posts, { element_size = size })
  print(("  element_size %.2f m (%d elements): %d nodes in tension first, %s after %d iterations"):format(
    size, fine.element_count, fine.history[1].tensile, fine.status, fine.iterations))
end

-- Figure 15 -----------------------------------------------------------------
print("Figure 15: hemispherical dome, R = 5 m, t = 0.5 m, 16 meridians, 8 courses, oculus 0.25 rad")
local dome = models.dome{ radius = 5, thickness = 0.5, meridians = 16, parallels = 8, oculus = 0.25 }
local dome_r, eq_seconds = timed(ashlar.analyze, dome)
local dome_fe, fe_seconds = timed(ashlar.fea, dome)
local dome_tied = ashlar.fea(dome, { relax = false })
print(("  equilibrium: stable = %s (%.3f s); FEA: %s after %d iterations (%.3f s)"):format(
  tostring(dome_r.stable), eq_seconds, dome_fe.status, dome_fe.iterations, fe_seconds))
local eq, elastic, before = courses.hoop_ratios(dome, dome_r.interfaces), courses.hoop_ratios(dome, dome_fe.interfaces),
  courses.hoop_ratios(dome, dome_tied.interfaces)
local rows = { "course,equilibrium,fea_relaxed,fea_tied" }
print("  | course | equilibrium | FEA, relaxed | FEA, every contact tied |")
print("  |---|---|---|---|")
for c = 1, #eq do
  rows[#rows + 1] = ("%d,%.6f,%.6f,%.6f"):format(c, eq[c], elastic[c], before[c])
  print(("  | %d | %.3f | %.3f | %.3f |"):format(c, eq[c], elastic[c], before[c]))
end
support.write_atomically(path("figure15_hoop_ratio.csv"), table.concat(rows, "\n") .. "\n")
draw_hoop_ratio()
ashlar.export(dome, path("figure15_equilibrium.glb"), { result = dome_r, forces = true })
if pictures then support.render(path("figure15_equilibrium.glb"), ABOVE) end
export(dome_fe, "figure15_fea", {}, ABOVE)
dome_fe:export(path("figure15_fea.vtu"))

-- Where the methods part ------------------------------------------------------
print("Arch thickness sweep: R = 5 m, 24 voussoirs, no sliding; FEA one element per voussoir")
local sweep = { "t_over_R,equilibrium_stable,equilibrium_s,fea_tension_nodes,fea_tied_s,all_status,all_iterations,all_s,largest_status,largest_iterations,largest_s" }
print("| t/R | equilibrium | time | FEA tied: nodes in tension | time | relaxed, release = all | time | relaxed, release = largest | time |")
print("|---|---|---|---|---|---|---|---|---|")
local STATUS_CODE = { compression_only = 1, tension = 0, mechanism = -1 }
for step = 0, 12 do
  local t_over_r = 0.08 + 0.01 * step
  local s = models.arch{ radius = 5, thickness = 5 * t_over_r, voussoirs = 24 }
  local eq_r, eq_s = timed(ashlar.analyze, s, NO_SLIDING)
  local fe_tied, tied_s = timed(ashlar.fea, s, { relax = false })
  local all, all_s = timed(ashlar.fea, s, { release = "all" })
  local largest, largest_s = timed(ashlar.fea, s, { release = "largest" })
  sweep[#sweep + 1] = ("%.2f,%d,%.4f,%d,%.4f,%d,%d,%.4f,%d,%d,%.4f"):format(t_over_r, eq_r.stable and 1 or 0, eq_s,
    tensile_count(fe_tied), tied_s, STATUS_CODE[all.status], all.iterations, all_s,
    STATUS_CODE[largest.status], largest.iterations, largest_s)
  print(("| %.2f | %s | %.3f s | %d | %.3f s | %s, %d it. | %.3f s | %s, %d it. | %.3f s |"):format(t_over_r,
    eq_r.stable and "stable" or "unstable", eq_s, tensile_count(fe_tied), tied_s, all.status, all.iterations,
    all_s, largest.status, largest.iterations, largest_s))
end
support.write_atomically(path("arch_methods.csv"), table.concat(sweep, "\n") .. "\n")
draw_arch_methods()
print("wrote " .. folder)
