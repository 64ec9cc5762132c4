-- The model gallery: one structure from every generator in the model library,
-- exported as glTF and rendered to a PNG by f3d (under xvfb-run, so no display
-- is needed).
--   ashlar scripts/gallery.lua [output folder] [glb folder]
-- Writes <name>.png to the output folder (default "gallery") and <name>.glb
-- to the glb folder (default: the output folder), for every generator of
-- require "ashlar.models" in sorted order, so generators added later show up
-- without changing this script. Without f3d or xvfb-run it says so, skips the
-- pictures and still writes the .glb files.
-- Blocks are coloured by height (viridis, over the free blocks; supports are
-- grey), and touching blocks get different shades of that colour (a greedy
-- colouring of the contact graph), so every joint shows.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local output = arg and arg[1] or "gallery"
local glb_folder = arg and arg[2] or output

-- Options for generators whose defaults make a poor picture; every other
-- generator is built with its defaults.
local OPTIONS = {
  -- The default wall (4.8 m x 0.7 m of 0.24 x 0.07 bricks) is a thin strip
  -- at gallery size; half as long and half as high again shows the bond.
  wall = { length = 2.4, height = 1.05 },
}

-- The view of each model (f3d's camera turned from the front, in degrees,
-- and its view angle: smaller zooms in); any other model gets DEFAULT_VIEW.
local DEFAULT_VIEW = { azimuth = 30, elevation = 25, angle = 24 }
local VIEWS = {
  arch = { azimuth = 30, elevation = 20, angle = 21 },
  column = { azimuth = 30, elevation = 20, angle = 34 },
  dome = { azimuth = 30, elevation = 25, angle = 22 },
  h_frame = { azimuth = 30, elevation = 20, angle = 30 },
  stack = { azimuth = 30, elevation = 20, angle = 32 },
  wall = { azimuth = 30, elevation = 20, angle = 22 },
  -- Checked on the drafts of these generators before they were registered.
  flying_buttress = { azimuth = 35, elevation = 15, angle = 30 },
  buttressed_vault = { azimuth = 25, elevation = 15, angle = 30 },
  groin_vault = { azimuth = 30, elevation = 25, angle = 28 },
}

local RESOLUTION = "800,600"

local shell_quoted = require("script_support").shell_quoted

local function exists(command)
  return os.execute("command -v " .. command .. " > /dev/null 2>&1") == true
end

-- Viridis at 11 stops, linearly interpolated.
local VIRIDIS = {
  { 0.267, 0.005, 0.329 }, { 0.283, 0.141, 0.458 }, { 0.254, 0.265, 0.530 },
  { 0.207, 0.372, 0.553 }, { 0.164, 0.471, 0.558 }, { 0.128, 0.567, 0.551 },
  { 0.135, 0.659, 0.518 }, { 0.267, 0.749, 0.441 }, { 0.478, 0.821, 0.318 },
  { 0.741, 0.873, 0.150 }, { 0.993, 0.906, 0.144 },
}

local function viridis(t)
  t = math.max(0, math.min(1, t)) * (#VIRIDIS - 1)
  local i = math.min(#VIRIDIS - 2, math.floor(t))
  local f, a, b = t - i, VIRIDIS[i + 1], VIRIDIS[i + 2]
  return { a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]), a[3] + f * (b[3] - a[3]) }
end

-- Brightness factors of the shades that tell touching blocks apart.
local SHADES = { 1.0, 0.72, 0.86, 0.6 }

-- One colour per block: hue from the height of its centroid among the free
-- blocks, shade from a greedy colouring of the contact graph (in block
-- order, each block takes the first shade that none of its already coloured
-- neighbours has; when all are taken, the least used among them).
local function colors(s)
  local n = #s
  local heights, low, high = {}, math.huge, -math.huge
  for i = 1, n do
    heights[i] = s:block(i):centroid()[3]
    if not s:is_support(i) then
      low, high = math.min(low, heights[i]), math.max(high, heights[i])
    end
  end
  local neighbours = {}
  for i = 1, n do neighbours[i] = {} end
  for _, f in ipairs(s:interfaces()) do
    table.insert(neighbours[f.a], f.b)
    table.insert(neighbours[f.b], f.a)
  end
  local shade, result = {}, {}
  for i = 1, n do
    local used = {}
    for k = 1, #SHADES do used[k] = 0 end
    for _, j in ipairs(neighbours[i]) do
      if shade[j] then used[shade[j]] = used[shade[j]] + 1 end
    end
    local best = 1
    for k = 2, #SHADES do
      if used[k] < used[best] then best = k end
    end
    shade[i] = best
    local c
    if s:is_support(i) then
      c = { 0.55, 0.55, 0.55 }
    else
      c = viridis(high > low and (heights[i] - low) / (high - low) or 0.5)
    end
    local factor = SHADES[best]
    result[i] = { c[1] * factor, c[2] * factor, c[3] * factor }
  end
  return result
end

-- glTF is y-up: ashlar's z becomes the file's +y (and y becomes -z), so f3d's
-- default up direction (+Y) puts ashlar's z up, and its default camera looks
-- at the x-z plane from ashlar's -y side (the front of an arch).
local function render(glb, png, view)
  local temporary = png .. ".tmp.png"
  local command = table.concat({
    "xvfb-run -a -s '-screen 0 1024x768x24' f3d", shell_quoted(glb),
    "--output", shell_quoted(temporary),
    "--resolution", RESOLUTION, "--bg-color 1,1,1", "--fxaa",
    "--camera-azimuth-angle", tostring(view.azimuth),
    "--camera-elevation-angle", tostring(view.elevation),
    "--camera-view-angle", tostring(view.angle),
    "> /dev/null 2>&1",
  }, " ")
  local ok = os.execute(command)
  if not ok then
    os.remove(temporary)
    error("f3d failed: " .. command)
  end
  assert(os.rename(temporary, png))
end

assert(os.execute("mkdir -p " .. shell_quoted(output) .. " " .. shell_quoted(glb_folder)),
       "cannot create " .. output .. " or " .. glb_folder)

local pictures = exists("f3d") and exists("xvfb-run")
if not pictures then
  print("f3d or xvfb-run not found: pictures are skipped, only the .glb files are written")
  print("  (on Debian: sudo apt-get install -y f3d xvfb)")
end

local names = {}
for name in pairs(models) do names[#names + 1] = name end
table.sort(names)

for _, name in ipairs(names) do
  local options = OPTIONS[name] or {}
  local start = ashlar.clock()
  local s = models[name](options)
  local seconds = ashlar.clock() - start
  local glb = glb_folder .. "/" .. name .. ".glb"
  ashlar.export(s, glb, { color = colors(s) })
  local line = ("%-16s %5d blocks, built in %6.1f ms: %s"):format(name, #s, seconds * 1e3, glb)
  if pictures then
    local png = output .. "/" .. name .. ".png"
    render(glb, png, VIEWS[name] or DEFAULT_VIEW)
    line = line .. ", " .. png
  end
  print(line)
end
