-- Tutorial 09: looking at results: the HTML viewer, glTF, drawings
-- (docs/guide/09_results.md).
-- usage: ashlar scripts/examples/09_results.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")
local files = os.tmpname()                 -- the pages and meshes go to a folder of their own
os.remove(files)
os.execute("mkdir -p '" .. files .. "'")
local function size(path)
  local f = assert(io.open(path, "rb"))
  local n = f:seek("end")
  f:close()
  return n
end

local arch = models.arch{ voussoirs = 15 }
local r = ashlar.analyze(arch, { friction = 0.7 })

-- The interactive viewer: one self-contained page.
ashlar.export(arch, files .. "/arch.html", { result = r, forces = true, thrust = true, interfaces = true })
-- The same objects as glTF, for any 3D viewer.
ashlar.export(arch, files .. "/arch.glb", { result = r, forces = true, thrust = true, edges = true })
local f = assert(io.open(files .. "/arch.glb", "rb"))
local magic = f:read(4)
f:close()
print(string.format("arch.html %.1f MB, arch.glb starts with %q", size(files .. "/arch.html") / 1e6, magic))

-- Drawings: an elevation with the thrust line and the forces.
ashlar.draw(arch, out .. "/09_arch_forces.svg", { result = r, forces = true, title = "15 voussoirs, friction 0.7" })

-- A drawing coloured by values, with its legend.
local dome = models.dome{ meridians = 12, parallels = 8 }
local v = ashlar.important_weights(dome)
local lo, hi = math.huge, -math.huge
for i = 1, #dome do
  if not dome:is_support(i) then lo, hi = math.min(lo, v[i]), math.max(hi, v[i]) end
end
print(string.format("dome: important weights from %.0f to %.0f N/m^3", lo, hi))
ashlar.draw(dome, out .. "/09_dome_weights.svg", { color = { values = v, map = "viridis", range = { 0, hi } },
                                                  title = "dome: important weights" })
ashlar.legend(out .. "/09_dome_legend.svg", { map = "viridis", range = { 0, hi }, label = "important weight (N/m³)" })
ashlar.export(dome, files .. "/dome.html", { color = { values = v, map = "viridis" }, legend = "N/m³" })
os.execute("rm -r '" .. files .. "'")

assert(magic == "glTF", "a binary glTF")
assert(r.stable, "the arch stands")
assert(math.abs(lo / 5507 - 1) < 1e-3 and math.abs(hi / 42046 - 1) < 1e-3, "important weights of the dome")
