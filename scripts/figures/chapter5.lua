-- The thesis's chapter 5 (Shin 2014, figures 12, 14, 15), remade with the
-- FEA, and the comparison of equilibrium and FEA over arch thickness:
--   ashlar scripts/figures/chapter5.lua [folder]     (default docs/figures/chapter5)
-- Writes per figure the FEA's deformed shape (.glb, tension nodes red,
-- released ones orange; a PNG when f3d and xvfb-run are installed), the
-- mesh with every result (.vtu, for ParaView), equilibrium drawings with
-- the thrust line, the dome's hoop-to-meridional chart and the thickness
-- sweep's chart, CSV and table (Markdown, printed).
local ashlar = require "ashlar"
local models = require "ashlar.models"
local courses = require "ashlar.models.courses"
package.path = (arg[0]:match("^(.*)/[^/]+/[^/]+$") or "..") .. "/?.lua;" .. package.path
local support = require "script_support"

local folder = arg[1] or "docs/figures/chapter5"
support.make_folders(folder)
local pictures = support.can_render()
if not pictures then print("f3d or xvfb-run not found: no PNG renderings of the .glb files") end
local NO_SLIDING = { friction = math.huge }
local FRONT = { azimuth = 0, elevation = 0 }
local ABOVE = { azimuth = 0, elevation = 30 }

local function path(name) return ("%s/%s"):format(folder, name) end

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
describe_relaxation("relaxation, the thesis's rule (release = all)", ashlar.fea(arch))
local relaxed = ashlar.fea(arch, { release = "largest" })
describe_relaxation("relaxation, one interface at a time (release = largest)", relaxed)
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
support.chart(path("figure15_hoop_ratio"), ([[
set datafile separator ","
set title "Hemispherical dome (R = 5 m, t = 0.5 m, 16 x 8, oculus): hoop / meridional force per course"
set xlabel "course (1 = bottom)"
set ylabel "mean hoop-joint force / mean bed-joint force (dimensionless)"
set grid
set key top left
set xtics 1
plot "%s" using 1:2 skip 1 with linespoints lw 2 pt 7 title "equilibrium", \
     "%s" using 1:3 skip 1 with linespoints lw 2 pt 5 title "FEA after relaxation", \
     "%s" using 1:4 skip 1 with linespoints lw 1 dt 2 pt 4 title "FEA, every contact tied (negative: hoop tension)"
]]):format(path("figure15_hoop_ratio.csv"), path("figure15_hoop_ratio.csv"), path("figure15_hoop_ratio.csv")))
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
support.chart(path("arch_methods"), ([[
set datafile separator ","
set title "Semicircular arch, 24 voussoirs: equilibrium against FEA with constraint relaxation\nstatus: equilibrium stable or not; FEA compression-only, tension remaining, or a mechanism after relaxation"
set xlabel "t/R (thickness over centreline radius)"
set ylabel "status"
set y2label "relaxation iterations"
set ytics ("mechanism" -1, "unstable / tension remains" 0, "stable / compression-only" 1)
set y2tics
set yrange [-1.5:1.5]
set y2range [0:*]
set grid
set key bottom right
set arrow from 0.1075, graph 0 to 0.1075, graph 1 nohead dt 3 lc rgb "#888888"
set label "t/R = 0.1075 (Milankovitch)" at 0.1085, graph 0.95 tc rgb "#666666"
f = "%s"
plot f using 1:2 skip 1 with linespoints lw 2 pt 7 title "equilibrium", \
     f using 1:($6 - 0.05) skip 1 with linespoints lw 2 pt 5 title "FEA, release = all", \
     f using 1:($9 + 0.05) skip 1 with linespoints lw 2 pt 9 title "FEA, release = largest", \
     f using 1:7 skip 1 axes x1y2 with impulses lw 3 lc rgb "#ff7f0e" title "iterations (all)", \
     f using ($1 + 0.002):10 skip 1 axes x1y2 with impulses lw 3 lc rgb "#2ca02c" title "iterations (largest)"
]]):format(path("arch_methods.csv")))
print("wrote " .. folder)
