-- Block and interface counts, build, contact-detection and analysis times of
-- every model generator at its defaults and at 10x refinement of its
-- discretisation (each count option times 10; the wall's bricks 10x smaller
-- in both directions). For planar models, also the speed-up of the planar
-- solve (3 equations per block) over the general one (6) and the difference
-- of their infeasibilities. Prints a table and writes a CSV (arg[1],
-- default bench_models.csv).
--   ashlar scripts/bench_models.lua [csv path]
local ashlar = require "ashlar"
local models = require "ashlar.models"

-- The options that refine each generator tenfold; nil: nothing to refine.
local REFINED = {
  arch = { voussoirs = 240 },
  arch_bridge = { voussoirs = 260, pier_courses = 40 },
  barrel_vault = { voussoirs = 240, courses = 60 },
  buttressed_vault = { voussoirs = 150, pier_blocks = 10, flyer_voussoirs = 60, buttress_blocks = 10 },
  column = { drums = 60 },
  dome = { meridians = 160, parallels = 180 },
  flying_buttress = { voussoirs = 600, pier_blocks = 40 },
  groin_vault = { voussoirs = 220, courses = 40 },
  h_frame = { courses = 49 },
  post_and_lintel = nil,
  stack = { blocks = 50, offset = 0.01 },
  wall = { brick = { 0.024, 0.007 } },
}

-- The fastest of enough analyses to fill about 0.2 s (small models take
-- milliseconds, where one run is mostly noise).
local function timed_analysis(s)
  local r = ashlar.analyze(s)
  local best = r.seconds
  for _ = 2, math.min(20, math.ceil(0.2 / math.max(r.seconds, 1e-3))) do
    best = math.min(best, ashlar.analyze(s).seconds)
  end
  return r, best
end

local function measure(name, options)
  local t0 = ashlar.clock()
  local s = models[name](options)
  local t1 = ashlar.clock()
  local interfaces = #s:interfaces()
  local t2 = ashlar.clock()
  local r, seconds = timed_analysis(s)
  local m = { blocks = #s, interfaces = interfaces, build = t1 - t0, contacts = t2 - t1, analysis = seconds,
              stable = r.stable, status = r.status, planar = s:is_planar() }
  if m.planar then
    -- The same structure through the general 6-equation solve.
    s:set_planar(false)
    local general, general_seconds = timed_analysis(s)
    m.speedup = general_seconds / seconds
    m.same_answer = general.stable == r.stable and math.abs(general.infeasibility - r.infeasibility)
  end
  return m
end

local names = {}
for name in pairs(models) do names[#names + 1] = name end
table.sort(names)

local rows = { "model,refinement,blocks,interfaces,build_s,contacts_s,analysis_s,planar,planar_speedup,"
              .. "infeasibility_difference,stable,status" }
print(("%-16s %-8s %7s %10s %9s %10s %10s %8s %9s  %s"):format("model", "", "blocks", "interfaces",
  "build s", "contacts s", "analysis s", "planar x", "|d inf|", "stable / status"))
for _, name in ipairs(names) do
  for _, case in ipairs{ { "default", {} }, { "10x", REFINED[name] } } do
    if case[2] then
      local m = measure(name, case[2])
      local speedup = m.speedup and ("%.2f"):format(m.speedup) or "-"
      local difference = m.speedup and (m.same_answer and ("%.1e"):format(m.same_answer) or "differs") or "-"
      print(("%-16s %-8s %7d %10d %9.4f %10.4f %10.4f %8s %9s  %s / %s"):format(name, case[1], m.blocks,
        m.interfaces, m.build, m.contacts, m.analysis, speedup, difference, tostring(m.stable), m.status))
      rows[#rows + 1] = ("%s,%s,%d,%d,%.6f,%.6f,%.6f,%s,%s,%s,%s,%s"):format(name, case[1], m.blocks,
        m.interfaces, m.build, m.contacts, m.analysis, tostring(m.planar), m.speedup and ("%.3f"):format(m.speedup) or "",
        difference, tostring(m.stable), m.status)
    end
  end
end

local path = arg[1] or "bench_models.csv"
require("script_support").write_atomically(path, table.concat(rows, "\n") .. "\n")
print("wrote " .. path)
