-- Two collapses by ashlar.simulate, for the README: a semicircular arch
-- below its minimum thickness, and a brick wall whose ground shakes across
-- it. Writes each as an animated glTF and a sequence of PNG frames.
--   ashlar scripts/simulate_collapse.lua [folder (default docs/figures/dynamics)]
local ashlar = require "ashlar"
local models = require "ashlar.models"

local folder = arg[1] or "docs/figures/dynamics"
os.execute(("mkdir -p %q"):format(folder))

-- Frames nearest the given times, drawn along `view`, with the time as title.
local function frames(sim, name, times, view)
  local path_times = sim:trajectory(1).times
  for _, t in ipairs(times) do
    local k = 1
    for j, tj in ipairs(path_times) do
      if math.abs(tj - t) < math.abs(path_times[k] - t) then k = j end
    end
    local path = ("%s/%s_%03d.png"):format(folder, name, math.floor(path_times[k] * 100 + 0.5))
    ashlar.draw(sim:structure(k), path, { view = view, width = 480, height = 320,
                                          title = ("t = %.1f s"):format(path_times[k]) })
    print("wrote " .. path)
  end
end

-- 16 voussoirs, t/R 0.09 (the minimum is 0.107): five hinges, then it falls.
local arch = models.arch{ radius = 5, thickness = 0.45, voussoirs = 16 }
local sim = ashlar.simulate(arch, { duration = 2, friction = 0.7, progress = true })
print(("arch: %s, largest displacement %.3f m, %d steps in %.1f s"):format(tostring(sim.moved),
  sim.max_displacement, sim.steps, sim.seconds))
sim:export(folder .. "/arch_collapse.glb", { fps = 30 })
frames(sim, "arch", { 0, 0.6, 1.0, 1.4 }, "front")

-- A running-bond wall, 10 bricks long, 10 courses, 0.11 m thick: it rocks
-- out of its plane once the ground accelerates across it by more than
-- g b/h = 0.16 g; at 0.5 g, 2 Hz it falls over.
-- It stands on a floor 3 m wide, so that it lands on it.
local wall = models.wall{ length = 2.4, height = 0.7, ground = false }
local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
for i = 1, #wall do
  for _, p in ipairs(wall:block(i):vertices()) do
    for k = 1, 3 do lo[k], hi[k] = math.min(lo[k], p[k]), math.max(hi[k], p[k]) end
  end
end
wall:add(ashlar.box{ size = { hi[1] - lo[1] + 0.4, 3, 0.1 },
                     center = { (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2, lo[3] - 0.05 } },
         { support = true, name = "floor" })
local quake = ashlar.simulate(wall, { duration = 1.2, friction = 0.6, progress = true,
  ground_acceleration = function(t) return 0, 0.5 * 9.81 * math.sin(2 * math.pi * 2 * t), 0 end })
print(("wall: %s, largest displacement %.3f m, %d steps in %.1f s"):format(tostring(quake.moved),
  quake.max_displacement, quake.steps, quake.seconds))
quake:export(folder .. "/wall_quake.glb", { fps = 30 })
frames(quake, "wall", { 0, 0.4, 0.8, 1.2 }, "side")
