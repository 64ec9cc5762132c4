-- Tutorial 08: studies, charts and regression suites (docs/guide/08_studies.md).
-- usage: ashlar scripts/examples/08_studies.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")
local work = os.tmpname()                  -- the database and the check folder
os.remove(work)
os.execute("mkdir -p '" .. work .. "/checks'")

-- A sweep: 3 voussoir counts x 21 thicknesses, kept in SQLite.
local study = ashlar.study{
  name = "arch_thickness",
  params = { t = ashlar.range(0.09, 0.11, 21), n = { 8, 16, 64 } },
  run = function(p)
    local r = ashlar.analyze(models.arch{ radius = 1, thickness = p.t, voussoirs = p.n }, { friction = math.huge })
    return { stable = r.stable, infeasibility = r.infeasibility }
  end,
  db = work .. "/arch.sqlite", workers = 1, progress = false,
}
local rows = study:rows()
local thinnest = {}
for _, row in ipairs(rows) do
  if row.stable and (not thinnest[row.n] or row.t < thinnest[row.n]) then thinnest[row.n] = row.t end
end
for _, n in ipairs{ 8, 16, 64 } do
  print(string.format("%2d voussoirs: thinnest stable t/R in the sweep %.3f", n, thinnest[n]))
end
local c = study:chart{ path = out .. "/08_arch_thickness.svg", x = "t", y = "infeasibility", series = "n",
                       title = "Semicircular arch, no sliding", x_label = "t / R" }
print(string.format("%d rows, %d series, %d skipped", #rows, #c.series, c.skipped))

-- A regression suite of one check script, run by `ashlar test`.
local f = assert(io.open(work .. "/checks/arch.lua", "w"))
f:write([[
local ashlar = require "ashlar"
local models = require "ashlar.models"
local check = require "ashlar.regression"
local f = ashlar.load_factor(models.arch{ radius = 1, thickness = 0.15, voussoirs = 64 }, { friction = math.huge })
check("t/R 0.15: status", f.status)
check("t/R 0.15: load factor", f.factor, { reference = 0.1446973, reference_tolerance = 1e-6 })
]])
f:close()
local function ashlar_test(options)
  local pipe = assert(io.popen("'" .. arg[-1] .. "' test " .. options .. " '" .. work .. "/checks' 2>&1"))
  local text = pipe:read("a")
  local ok = pipe:close()
  return text, ok
end
local first = ashlar_test("--update")
local second, passed = ashlar_test("")
print(second:match("[^\n]*passed[^\n]*"))
os.execute("rm -r '" .. work .. "'")

-- The minima the chapter quotes, for polyhedral voussoirs.
local minima = { [8] = 0.09997, [16] = 0.10708, [64] = 0.10738 }
for _, n in ipairs{ 8, 16, 64 } do
  local g = ashlar.geometric_factor(function(t) return models.arch{ radius = 1, thickness = t, voussoirs = n } end,
                                    0.15, { friction = math.huge })
  print(string.format("%2d voussoirs: minimum t/R %.5f", n, g.minimum))
  assert(math.abs(g.minimum - minima[n]) < 1e-5, "minimum thickness of " .. n .. " voussoirs")
end

assert(#rows == 63 and #c.series == 3 and c.skipped == 0, "the sweep")
assert(math.abs(thinnest[8] - 0.100) < 1e-9 and math.abs(thinnest[16] - 0.108) < 1e-9
       and math.abs(thinnest[64] - 0.108) < 1e-9, "thinnest stable arches (minima 0.09997, 0.10708, 0.10738)")
assert(passed and second:find("2 passed, 0 failed", 1, true), "the regression suite passes: " .. first .. second)
