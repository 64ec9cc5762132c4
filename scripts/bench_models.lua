-- Block and interface counts, build, contact-detection and analysis times of
-- every model generator at its defaults and at 10x refinement of its
-- discretisation (each count option times 10; the wall's bricks 10x smaller
-- in both directions). Prints a table and writes a CSV (arg[1], default
-- bench_models.csv).
--   ashlar scripts/bench_models.lua [csv path]
local ashlar = require "ashlar"
local models = require "ashlar.models"

-- The options that refine each generator tenfold; nil: nothing to refine.
local REFINED = {
  arch = { voussoirs = 310 },
  arch_bridge = { voussoirs = 210, pier_courses = 40 },
  barrel_vault = { voussoirs = 150, courses = 60 },
  column = { drums = 60 },
  dome = { meridians = 160, parallels = 160 },
  flying_buttress = { voussoirs = 480, pier_blocks = 40 },
  groin_vault = { voussoirs = 160, courses = 40 },
  h_frame = { courses = 49 },
  post_and_lintel = nil,
  stack = { blocks = 50, offset = 0.01 },
  wall = { brick = { 0.024, 0.007 } },
}

local function measure(name, options)
  local t0 = ashlar.clock()
  local s = models[name](options)
  local t1 = ashlar.clock()
  local interfaces = #s:interfaces()
  local t2 = ashlar.clock()
  local r = ashlar.analyze(s)
  return { blocks = #s, interfaces = interfaces, build = t1 - t0, contacts = t2 - t1,
           analysis = r.seconds, stable = r.stable, status = r.status, planar = s:is_planar() }
end

local names = {}
for name in pairs(models) do names[#names + 1] = name end
table.sort(names)

local rows = { "model,refinement,blocks,interfaces,build_s,contacts_s,analysis_s,planar,stable,status" }
print(("%-16s %-9s %7s %10s %9s %10s %10s  %s"):format("model", "", "blocks", "interfaces",
  "build s", "contacts s", "analysis s", "stable / status"))
for _, name in ipairs(names) do
  for _, case in ipairs{ { "default", {} }, { "10x", REFINED[name] } } do
    if case[2] then
      local m = measure(name, case[2])
      print(("%-16s %-9s %7d %10d %9.4f %10.4f %10.3f  %s / %s%s"):format(name, case[1], m.blocks,
        m.interfaces, m.build, m.contacts, m.analysis, tostring(m.stable), m.status,
        m.planar and " (planar)" or ""))
      rows[#rows + 1] = ("%s,%s,%d,%d,%.6f,%.6f,%.6f,%s,%s,%s"):format(name, case[1], m.blocks,
        m.interfaces, m.build, m.contacts, m.analysis, tostring(m.planar), tostring(m.stable), m.status)
    end
  end
end

local path = arg[1] or "bench_models.csv"
local file = assert(io.open(path .. ".tmp", "w"))
file:write(table.concat(rows, "\n"), "\n")
file:close()
assert(os.rename(path .. ".tmp", path))
print("wrote " .. path)
