-- Time of each chapter-4 analysis (Shin 2014) on an arch of 31 voussoirs
-- (no sliding) and a dome of 16 x 24 blocks (friction 0.7):
--   ashlar scripts/bench_weights.lua
-- Prints one line per analysis and structure. The dome's important_weights
-- and load_capacity take minutes.
--
-- With `margins`, the four margins and weight analyses at 3D scale instead
-- (issue 27): load_factor (pushed along x), friction_demand, load_capacity
-- and important_weights on models.dome{} (305 blocks), on an imperfect copy
-- of it (every vertex moved by up to 0.1 % of its block's size, as models
-- from the field come: no symmetry) and on a running-bond barrel vault of
-- 1,008 voussoirs (32 around, 31 courses of 0.5 m) and on a dome of 16 x 24
-- blocks (friction 0.7; dome24), with their answers and
-- wall and CPU times (the process's, so on 2 cores CPU may be twice wall).
-- load_capacity and important_weights run twice: one block per orbit of
-- the problem's symmetries (the default), and every block
-- (`symmetry = false`). The counts (programs, solves, interior-point and
-- simplex iterations) do not depend on the machine's load. A third
-- argument, dome, imperfect, vault or dome24, runs that structure alone:
--   ashlar scripts/bench_weights.lua margins [dome|imperfect|vault|dome24]
-- With `friction`, friction_demand alone on ten structures (below), run
-- from the repository's root.
-- With `blocks`, load_capacity and important_weights of the blocks asked
-- (option `blocks`) without the symmetries: one block, then a whole course
-- (the middle one of the 1,008-voussoir vault, 32 blocks; course 9 of the
-- imperfect dome, 16), with wall and CPU time per block asked; with
-- `blocks check`, also every block's load capacity (minutes on the vault)
-- and the largest relative difference of the course's bounds against it:
--   ashlar scripts/bench_weights.lua blocks [check]
local ashlar = require "ashlar"
local models = require "ashlar.models"

-- The CPU seconds of this process so far (user + system), from /proc.
local function cpu_seconds()
  local f = io.open("/proc/self/stat")
  if not f then return 0 / 0 end
  local fields = {}
  for field in f:read("a"):gsub("^.*%) ", ""):gmatch("%S+") do fields[#fields + 1] = field end
  f:close()
  return (tonumber(fields[12]) + tonumber(fields[13])) / 100  -- utime, stime in clock ticks (USER_HZ 100)
end
-- The imperfect dome's contacts: a joint between blocks a and b opens
-- or closes by at most the amount times size_a + size_b (each vertex
-- moves by up to the amount times its block's size), so a tolerance 2.5
-- times the amount times the largest block's size covers every joint.
-- (The mean block size, as tests/lua/perturbed_spec.lua takes for its
-- vault of equal blocks, left one joint of the dome's larger lower
-- courses open by 4.703e-6 against 4.696e-6.)
local function imperfect(amount)
  local s = models.perturbed(models.dome{}, { amount = amount, seed = 1 })
  local largest = 0
  for i = 1, #s do
    local lo, hi = s:block(i):bounds()
    largest = math.max(largest, math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2))
  end
  return s, { contact_tolerance = 2.5 * amount * largest }
end
-- With `friction`, ashlar.friction_demand alone (default bracket 1e-6) on
-- the structures of docs/performance.md's table: its demand, bracket,
-- programs and iterations, wall and CPU time of each.
if arg[1] == "friction" then
  local wall3d = models.wall{ length = 4.8, height = 1.47 }
  wall3d:set_planar(false)
  local cases = {
    { "dome 16 x 18", models.dome{}, {} },
    { "dome 16 x 24", models.dome{ meridians = 16, parallels = 24 }, {} },
    { "dome 16 x 18, every vertex moved by up to 0.1 %", imperfect(1e-3) },
    { "barrel vault 32 x 15, running bond",
      models.barrel_vault{ voussoirs = 32, courses = 15, length = 7.5, bond = "running" }, {} },
    { "barrel vault 32 x 31, running bond",
      models.barrel_vault{ voussoirs = 32, courses = 31, length = 15.5, bond = "running" }, {} },
    { "barrel vault 16 x 8", models.barrel_vault{ voussoirs = 16, courses = 8 }, {} },
    { "groin vault", models.groin_vault{}, {} },
    { "Armadillo vault (tests/data/compas_cra)",
      ashlar.import("tests/data/compas_cra/armadillo_cra.json", { planarity = 0.05, interfaces = "detect" }),
      { contact_tolerance = 0.03 } },
    { "wall of 431 blocks, 3D", wall3d, {} },
    { "the same wall, planar", models.wall{ length = 4.8, height = 1.47 }, {} },
  }
  for _, case in ipairs(cases) do
    local name, s, options = case[1], case[2], case[3]
    options.progress = false
    local wall, cpu = ashlar.clock(), cpu_seconds()
    local d = ashlar.friction_demand(s, options)
    print(("%-50s %.10g [%.10g] %s, %d programs, %d iterations, %.2f s wall, %.2f s CPU"):format(name, d.friction,
      d.lower, d.status, d.programs, d.iterations, ashlar.clock() - wall, cpu_seconds() - cpu))
  end
  return
end

if arg[1] == "blocks" then
  local perturbed, perturbed_contact = imperfect(1e-3)
  local vault = models.barrel_vault{ voussoirs = 32, courses = 31, length = 15.5, bond = "running" }
  local cases = {
    { "barrel vault, running bond, 32 x 31", vault, {}, "voussoir %d course 16", 32 },
    { "dome 16 x 18, every vertex moved by up to 0.1 %", perturbed, perturbed_contact, "course 9 block %d", 16 },
  }
  for _, case in ipairs(cases) do
    local name, s, contact, pattern, count = case[1], case[2], case[3], case[4], case[5]
    local course = {}
    for k = 1, count do course[k] = assert(s:find(pattern:format(k))) end
    local function options(extra)
      local o = { progress = false, symmetry = false }
      for k, v in pairs(contact) do o[k] = v end
      for k, v in pairs(extra) do o[k] = v end
      return o
    end
    print(name)
    local answers = {}
    for _, asked in ipairs{ { course[1] }, course } do
      for _, run in ipairs{ { "load_capacity", ashlar.load_capacity }, { "important_weights", ashlar.important_weights } } do
        local wall, cpu = ashlar.clock(), cpu_seconds()
        answers[run[1]] = run[2](s, options{ blocks = asked })
        wall, cpu = ashlar.clock() - wall, cpu_seconds() - cpu
        print(("  %-18s %2d blocks asked %8.2f s wall %8.2f s CPU, %.3f s wall a block"):format(run[1], #asked, wall,
          cpu, wall / #asked))
      end
    end
    if arg[2] == "check" then
      local wall = ashlar.clock()
      local every = ashlar.load_capacity(s, options{})
      local worst = 0
      for _, i in ipairs(course) do
        for _, bound in ipairs{ "min", "max" } do
          local a, b = answers.load_capacity[i][bound], every[i][bound]
          if a ~= b then worst = math.max(worst, math.abs(a - b) / math.abs(b)) end
        end
      end
      print(("  every block's load_capacity %.2f s wall; the blocks asked within %.3g relative"):format(
        ashlar.clock() - wall, worst))
    end
  end
  return
end

if arg[1] == "margins" then
  local perturbed, perturbed_contact = imperfect(1e-3)
  local structures = {
    { "dome", "dome 16 x 18", models.dome{}, {} },
    { "imperfect", "dome 16 x 18, every vertex moved by up to 0.1 %", perturbed, perturbed_contact },
    { "vault", "barrel vault, running bond, 32 x 31",
      models.barrel_vault{ voussoirs = 32, courses = 31, length = 15.5, bond = "running" }, {} },
    { "dome24", "dome 16 x 24", models.dome{ meridians = 16, parallels = 24 }, {} },
  }
  local only = arg[2]
  local keys, known = {}, {}
  for _, case in ipairs(structures) do
    keys[#keys + 1] = case[1]
    known[case[1]] = true
  end
  if only and not known[only] then
    error(("structure: expected one of %s, got %s"):format(table.concat(keys, ", "), only))
  end
  for _, case in ipairs(structures) do
    local key, name, s, contact = case[1], case[2], case[3], case[4]
    if only and key ~= only then goto next end
    local function options(extra)
      local o = { progress = false }
      for k, v in pairs(contact) do o[k] = v end
      for k, v in pairs(extra or {}) do o[k] = v end
      return o
    end
    local free = 0
    for i = 1, #s do if not s:is_support(i) then free = free + 1 end end
    print(("%s (%d free blocks)"):format(name, free))
    local function load_capacity(extra)
      return function()
          local cap = ashlar.load_capacity(s, options(extra))
          local finite, unbounded, least, most = 0, 0, math.huge, 0
          for i = 1, #s do
            if cap[i] then
              if cap[i].max == math.huge then unbounded = unbounded + 1 else
                finite = finite + 1
                least, most = math.min(least, cap[i].max), math.max(most, cap[i].max)
              end
            end
          end
          return ("%d finite maxima in [%.6g, %.6g], %d unbounded (%s, %d programs, %d iterations, %d symmetries)")
            :format(finite, least, most, unbounded, cap.status, cap.programs, cap.iterations, cap.symmetries)
        end
    end
    local function important_weights(extra)
      return function()
          local v = ashlar.important_weights(s, options(extra))
          local most = 0
          for i = 1, #s do most = math.max(most, v[i]) end
          return ("largest %.6g N/m^3 (%s, %d solves, %d iterations, %d symmetries)"):format(most, v.status, v.solves,
            v.iterations, v.symmetries)
        end
    end
    local runs = {
      { "load_factor", function()
          local f = ashlar.load_factor(s, options())
          return ("factor %.10g (%s, %d iterations)"):format(f.factor, f.status, f.iterations)
        end },
      { "friction_demand", function()
          local d = ashlar.friction_demand(s, options())
          return ("friction %.10g (%s, %d programs)"):format(d.friction, d.status, d.programs)
        end },
      { "load_capacity", load_capacity() },
      { "  every block", load_capacity{ symmetry = false } },
      { "important_weights", important_weights() },
      { "  every block", important_weights{ symmetry = false } },
    }
    for _, run in ipairs(runs) do
      local wall, cpu = ashlar.clock(), cpu_seconds()
      local answer = run[2]()
      print(("  %-18s %8.2f s wall %8.2f s CPU  %s"):format(run[1], ashlar.clock() - wall, cpu_seconds() - cpu,
        answer))
    end
    ::next::
  end
  return
end

local cases = {
  { "arch, 31 voussoirs", models.arch{ radius = 5, thickness = 0.6, voussoirs = 31 }, { friction = math.huge },
    "voussoir 8", "voussoir 16" },
  { "dome 16 x 24", models.dome{ meridians = 16, parallels = 24 }, {}, "course 12 block 1", "course 12 block 1" },
}

local function timed(what, f)
  local start = ashlar.clock()
  f()
  return what, ashlar.clock() - start
end

for _, case in ipairs(cases) do
  local name, s, options, block, loaded = case[1], case[2], case[3], case[4], case[5]
  local free = 0
  for i = 1, #s do if not s:is_support(i) then free = free + 1 end end
  print(("%s (%d free blocks)"):format(name, free))
  local analysis = ashlar.analyze(s, options)
  local sensitivity = ashlar.weight_sensitivity(s, loaded, options)
  print(("  %-26s %9.4f s  (after the analysis, %.3f s)"):format("weight_sensitivity", sensitivity.seconds,
                                                                    analysis.seconds))
  for _, run in ipairs{
    { timed("necessary_weights", function() ashlar.necessary_weights(s, block, options) end) },
    { timed("important_weights", function() ashlar.important_weights(s, options) end) },
    { timed("trace_loads, 200 traces", function() ashlar.trace_loads(s, loaded, { traces = 200, seed = 1 }) end) },
    { timed("load_capacity", function() ashlar.load_capacity(s, options) end) },
  } do
    print(("  %-26s %9.4f s"):format(run[1], run[2]))
  end
end
