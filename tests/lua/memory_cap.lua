-- The sandbox's memory cap across the bindings, in a stock lua5.4 with the
-- ashlar C module (run: lua5.4 memory_cap.lua; ASHLAR_MODULE_DIR is the
-- folder of ashlar.so). That Lua is compiled as C: an error is a longjmp,
-- which skips the destructors of any C++ object alive in the frames it
-- crosses. Each case below is a script run by ashlar.sandbox with its Lua
-- heap capped at evenly spaced values from what an empty sandboxed state
-- needs to the least the script runs with (found by bisection), so that
-- the allocation that fails moves through every part of each binding
-- call; a first sweep below the empty state's need fails while the state
-- is made. Every run must end in its results or in the memory limit's
-- error, never another error or a crash; under the sanitizers (ctest in
-- the ASHLAR_SANITIZE build) a destructor skipped is a leak that fails the
-- run at exit.
--
-- ASHLAR_MEMORY_CAP_STEPS sets how many caps each case runs (default 150).
package.cpath = assert(os.getenv("ASHLAR_MODULE_DIR"), "set ASHLAR_MODULE_DIR to the folder of ashlar.so")
  .. "/?.so;" .. package.cpath
local ashlar = require "ashlar"

local steps = tonumber(os.getenv("ASHLAR_MEMORY_CAP_STEPS") or "150")
local folder = os.tmpname()
os.remove(folder)
assert(os.execute("mkdir -p '" .. folder .. "'"))

-- Three boxes stacked on a support; each case starts from it.
local stack = [[
local ashlar = require "ashlar"
local s = ashlar.structure()
for i = 1, 3 do
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.05 * i, 0, 0.25 + 0.5 * (i - 1) } }, { support = i == 1 })
end
local folder = ...
]]

-- name, script (after `stack`), what the uncapped run returns and, by
-- position, another result allowed when the cap bites.
local cases = {
  { "block", [[
local b = ashlar.block{ vertices = { {0,0,0}, {1,0,0}, {1,1,0}, {0,1,0}, {0,0,1}, {1,0,1}, {1,1,1}, {0,1,1} },
                        faces = { {1,4,3,2}, {5,6,7,8}, {1,2,6,5}, {2,3,7,6}, {3,4,8,7}, {4,1,5,8} } }
local below, above = b:split({ 0, 0, 0.25 }, { 0, 0, 1 })
local moved = above:translated{ 1, 0, 0 }:rotated({ 0, 0, 1 }, 0.5, { 0, 0, 0 })
return b:volume(), below:mass(), #moved:vertices(), #moved:faces(), moved:centroid()[3]
]], { 1, 600, 8, 6, 0.625 } },
  { "structure", [[
local interfaces = s:interfaces{}
return #s, #interfaces, s:block(2):volume(), tostring(s):match("^Structure") ~= nil
]], { 3, 2, 0.5, true } },
  { "analyze", [[
local r = ashlar.analyze(s, { friction = 0.7 })
local line = r:thrust_line()
return r.stable, r.status, #r.interfaces, r.interfaces[1].normal_force > 0, #line
]], { true, "converged", 2, true, 2 } },
  { "result", [[
s:add_load{ block = 3, force = { 100, 0, 0 } }
local r = ashlar.analyze(s, { friction = 0.7 })
local report = s:contact_report{}
return #r.blocks, #r.vertices, r.timings.solve >= 0, tostring(r):match("^Result %(stable") ~= nil, #s:loads(),
       #report.overlaps, s:name(2) == "" or s:name(2) ~= nil
]], { 3, 8, true, true, 1, 0, true } },
  { "methods", [[
local g = ashlar.gradient(s)
local c = ashlar.compare_methods(s, { friction = 0.7 })
local f = ashlar.fea(s)
local sim = ashlar.simulate(s, { duration = 0.05 })
local flow = ashlar.trace_loads(s, 3, { traces = 4 })
return #g, g.stable, c.equilibrium.stable, c.kinematic.stable, f.total_weight, #f.nodes, sim.moved,
       #sim:trajectory(3).times, #flow.polylines
]], { 3, true, true, true, 23544, 16, false, 6, 4 } },
  { "models", [[
local models = require "ashlar.models"
local arch = models.arch{ radius = 1, thickness = 0.2, voussoirs = 8 }
return #arch, ashlar.analyze(arch).stable
]], { 10, true } },
  { "export", [[
s:save(folder .. "/stack.json")
local loaded = ashlar.load(folder .. "/stack.json")
ashlar.export(loaded, folder .. "/stack.glb", { result = ashlar.analyze(loaded) })
ashlar.export_qp(loaded, folder .. "/stack.qps")
return #loaded, loaded:block(3):centroid()[3]
]], { 3, 1.25 } },
  { "study", [[
-- A run that runs out of memory is an error row, not the study's end.
local study = ashlar.study{ name = "stack", params = { f = { 0.3, 0.7 }, n = 1 }, progress = false,
                            run = function(p) return { stable = ashlar.analyze(s, { friction = p.f }).stable } end }
study:csv(folder .. "/stack.csv")
local rows, info = study:rows(), study:info()
return #rows, rows[2].stable or rows[2].run_status, info.ok + info.errors, ashlar.range(0, 1, 3)[2],
       #ashlar.latin_hypercube({ x = { min = 0, max = 1 } }, { samples = 4 })
]], { 2, true, 2, 0.5, 4 }, { [2] = "error" } },
  { "search", [[
local models = require "ashlar.models"
local tilted = ashlar.tilt(s, 0.1)
local g = ashlar.geometric_factor(function(t)
  return models.arch{ radius = 1, thickness = t, voussoirs = 8 }
end, 0.2, { tolerance = 0.01, friction = math.huge })
return #tilted, g.status, math.floor(g.minimum * 100 + 0.5) / 100
]], { 3, "converged", 0.1 } },
  { "margins", [[
local lf = ashlar.load_factor(s, { friction = 0.7, direction = { 1, 0, 0 } })
local fd = ashlar.friction_demand(s)
local cap = ashlar.load_capacity(s, { friction = 0.7, threads = 1, progress = false })
local iw = ashlar.important_weights(s, { friction = 0.7, threads = 1, progress = false })
-- The middle block stands on its own: the top one's weight is not needed
-- (0 N/m^3 to the solver's tolerance, against its own 23,544 N/m^3).
return lf.factor, fd.friction, cap[3].max == math.huge, iw.status, iw[3] < 0.1
]], { 0.7, 0, true, "done", true } },
  { "pictures", [[
local rows = { { x = 1, y = 2 }, { x = 2, y = 3 }, { x = 3, y = 5 } }
local chart = ashlar.chart{ path = folder .. "/stack.png", data = rows, x = "x", y = "y" }
ashlar.draw(s, folder .. "/stack.svg", { result = ashlar.analyze(s) })
ashlar.legend(folder .. "/legend.png", { map = "viridis", range = { 0, 1 } })
ashlar.export(s, folder .. "/stack.obj")
local back = ashlar.import(folder .. "/stack.obj")
return chart.skipped, #back, math.floor(back:block(3):volume() * 1e6 + 0.5)
]], { 0, 3, 500000 } },
  { "errors", [[
-- Wrong arguments raise their own errors; running out of memory meanwhile
-- raises that instead, which these calls pass on.
local function message_of(...)
  local ok, message = pcall(...)
  if message:find("not enough memory", 1, true) then error(message, 0) end
  return message
end
return message_of(ashlar.box, { size = { 1, 1 } }):match("size: expected a table of 3 numbers") ~= nil,
       message_of(ashlar.analyze, s, { colour = 2 }):match("unknown option 'colour'") ~= nil,
       message_of(ashlar.study, { name = "bad name", params = { x = 1 }, run = print }):match("name: ") ~= nil
]], { true, true, true } },
}

local function same(a, b)
  if type(a) == "number" and type(b) == "number" then return math.abs(a - b) <= 1e-9 * math.max(1, math.abs(b)) end
  return a == b
end

-- Runs `script` after `stack` (or alone) with the heap capped at `memory`
-- (0: no cap).
local function sandbox(script, memory, alone)
  return ashlar.sandbox{ source = alone and script or stack .. script, args = { folder }, read = { folder },
                         write = { folder }, memory = memory }
end

local function describe(outcome)
  local parts = { outcome.status, outcome.message or "" }
  for i = 1, #outcome.results do parts[#parts + 1] = tostring(outcome.results[i]) end
  return table.concat(parts, " | ")
end

local failures = 0
local function fail(text)
  failures = failures + 1
  io.stderr:write(text, "\n")
end

-- Making the sandboxed state runs out of memory first, for caps up to what
-- an empty script needs: ashlar.sandbox then raises, saying so (or, made,
-- the state runs out running the script).
local empty = sandbox("return", 0, true).memory_peak
local started = os.clock()
for step = 0, steps do
  local cap = 1 + (empty - 1) * step // steps
  local ok, outcome = pcall(sandbox, "return", cap, true)
  local fine = not ok and outcome:find("memory", 1, true)
    or ok and (outcome.status == "ok" or outcome.status == "memory" and outcome.message:find("memory limit of", 1, true))
  if not fine then
    fail(("empty state, cap %d: %s"):format(cap, ok and describe(outcome) or outcome))
  end
end
print(("%-10s %3d runs capped at 1..%d bytes"):format("state", steps + 1, empty))
for _, case in ipairs(cases) do
  local name, script, expected = case[1], case[2], case[3]
  local free = sandbox(script, 0)
  local right = free.status == "ok" and #free.results == #expected
  for i = 1, #expected do right = right and same(free.results[i], expected[i]) end
  if not right then
    local shown = {}
    for i = 1, #expected do shown[i] = tostring(expected[i]) end
    fail(("%s: without a cap: %s (expected %s)"):format(name, describe(free), table.concat(shown, ", ")))
  else
    -- The least cap the script runs with (by bisection: more memory never
    -- hurts, to within when the collector runs); below it, each cap stops
    -- the script at another allocation.
    local low, high = empty, free.memory_peak
    while high - low > 1 do
      local middle = (low + high) // 2
      if sandbox(script, middle).status == "ok" then high = middle else low = middle end
    end
    local counts = { ok = 0, memory = 0 }
    for step = 0, steps do
      local cap = empty + (high - empty) * step // steps
      local outcome = sandbox(script, cap)
      counts[outcome.status] = (counts[outcome.status] or 0) + 1
      if outcome.status == "memory" then
        if not (outcome.message or ""):find("memory limit of", 1, true) then
          fail(("%s, cap %d: the memory error came back as %q"):format(name, cap, outcome.message))
        end
      elseif outcome.status == "ok" then
        for i = 1, #expected do
          local also = case[4] and case[4][i]
          if not (same(outcome.results[i], free.results[i]) or (also ~= nil and outcome.results[i] == also)) then
            fail(("%s, cap %d: other results: %s"):format(name, cap, describe(outcome)))
            break
          end
        end
      else
        fail(("%s, cap %d: %s"):format(name, cap, describe(outcome)))
      end
    end
    if counts.memory < steps // 2 then fail(("%s: only %d of %d runs hit the cap"):format(name, counts.memory, steps + 1)) end
    print(("%-10s %3d runs capped at %d..%d bytes: %d ran out of memory, %d finished"):format(
      name, steps + 1, empty, high, counts.memory, counts.ok))
  end
end
print(("%.1f s of CPU"):format(os.clock() - started))
os.execute("rm -rf '" .. folder .. "'")
if failures > 0 then
  io.stderr:write(failures, " failures\n")
  os.exit(1)
end
