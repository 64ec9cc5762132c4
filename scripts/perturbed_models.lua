-- Imperfect models, as CAD and scans deliver them: every vertex of every
-- free block of a generated barrel vault and dome moved at random by up to
-- 1 % of its block's size (warped faces, gaps and overlaps of that order),
-- written to OBJ and to a COMPAS assembly (contacts left to detection) and
-- imported back with `planarity`, then compared with the
-- unperturbed model: interfaces found (count, total area), and the verdict of
-- a thick (stable) and a thin (unstable) version. Then the time of contact
-- detection on a perturbed 10,027-block vault.
--   ashlar scripts/perturbed_models.lua [folder for the OBJ files (default /tmp)]
local ashlar = require "ashlar"
local models = require "ashlar.models"

local folder = arg[1] or "/tmp"
local AMOUNT = 0.01      -- of each block's size (bounding-box diagonal): the largest vertex move
local PLANARITY = 0.05   -- accepts faces warped by the moves (about 2 x AMOUNT of a face's size)
local TOLERANCE = 2.5    -- contact tolerance, in multiples of AMOUNT x the mean block size
local FRICTION = 0.7

local function block_size(b)
  local lo, hi = b:bounds()
  return math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
end

local function mean_block_size(s)
  local sum = 0
  for i = 1, #s do sum = sum + block_size(s:block(i)) end
  return sum / #s
end

-- Contact angle (rad): at least 15 degrees, and more for joints so thin
-- that the moves tilt their faces further. Two vertices across a joint of
-- width w (the model's thickness) moving AMOUNT x the block size in
-- opposite directions tilt a face by atan(2 x AMOUNT x size / w), largest
-- on the largest free blocks (supports do not move); the joint's two copies
-- may tilt opposite ways.
local function contact_angle(s, thickness)
  local largest = 0
  for i = 1, #s do
    if not s:is_support(i) then largest = math.max(largest, block_size(s:block(i))) end
  end
  return math.max(math.rad(15), 2 * math.atan(2 * AMOUNT * largest / thickness))
end

-- models.perturbed's copy of the model, through an OBJ file (the supports
-- keep their names and are picked by them on import) or a COMPAS assembly
-- (which flags its supports; its interfaces are left to detection).
local function perturbed_through(route, s, name, seed)
  local moved = models.perturbed(s, { amount = AMOUNT, seed = seed, planarity = PLANARITY })
  local path = ("%s/perturbed_%s.%s"):format(folder, name, route == "obj" and "obj" or "json")
  ashlar.export(moved, path)
  if route == "compas" then return ashlar.import(path, { planarity = PLANARITY, interfaces = "detect" }) end
  local supports = {}
  for i = 1, #s do
    if s:is_support(i) then supports[s:name(i)] = true end
  end
  return ashlar.import(path, { planarity = PLANARITY, support = function(n) return supports[n] == true end })
end

local function interfaces_of(s, tolerance, angle)
  local list = s:interfaces{ tolerance = tolerance, angle = angle }
  local area, pairs_seen, count = 0, {}, 0
  for _, c in ipairs(list) do
    area = area + c.area
    local key = c.a .. "," .. c.b
    if not pairs_seen[key] then pairs_seen[key], count = true, count + 1 end
  end
  return count, area
end

print(("every free block's vertices moved by up to %g of its size; planarity %g; contact tolerance %g x that move"):format(
  AMOUNT, PLANARITY, TOLERANCE))
print(("%-22s %-6s %6s %11s %13s %8s %8s %8s %9s %6s"):format("model", "route", "blocks", "pairs", "area m^2", "area %",
  "stable", "before", "tolerance", "angle"))
local cases = {
  { "barrel vault t/R 0.15", models.barrel_vault{ radius = 3, thickness = 0.45, voussoirs = 24, courses = 6, bond = "running" }, 0.45 },
  { "barrel vault t/R 0.09", models.barrel_vault{ radius = 3, thickness = 0.27, voussoirs = 24, courses = 6, bond = "running" }, 0.27 },
  { "dome t/R 0.1", models.dome{ radius = 5, thickness = 0.5 }, 0.5 },
  { "dome t/R 0.02", models.dome{ radius = 5, thickness = 0.1 }, 0.1 },
}
for index, case in ipairs(cases) do
  local name, s = case[1], case[2]
  local angle = contact_angle(s, case[3])
  local count, area = interfaces_of(s)
  local before = ashlar.analyze(s, { friction = FRICTION })
  for _, route in ipairs{ "obj", "compas" } do
    local p = perturbed_through(route, s, tostring(index), index)
    local tolerance = TOLERANCE * AMOUNT * mean_block_size(s)
    local found, found_area = interfaces_of(p, tolerance, angle)
    local ok, r = pcall(ashlar.analyze, p, { friction = FRICTION, contact_tolerance = tolerance, contact_angle = angle })
    print(("%-22s %-6s %6d %5d/%-5d %6.2f/%-6.2f %+7.2f %8s %8s %9.4f %6.1f"):format(name, route, #s, found, count, found_area,
      area, 100 * (found_area - area) / area, ok and tostring(r.stable) or "error", tostring(before.stable), tolerance,
      math.deg(angle)))
    if not ok then print("  " .. tostring(r)) end
  end
end

-- Contact detection at scale: a 10,027-block vault, perturbed in memory.
local big = models.barrel_vault{ radius = 2, thickness = 0.4, voussoirs = 50, courses = 200, length = 50, bond = "running" }
local moved = models.perturbed(big, { amount = AMOUNT, planarity = PLANARITY })
local tolerance = TOLERANCE * AMOUNT * mean_block_size(big)
local t0 = ashlar.clock()
local found, found_area = interfaces_of(moved, tolerance, contact_angle(big, 0.4))
local seconds = ashlar.clock() - t0
local count, area = interfaces_of(big)
print(("%d-block vault: %d of %d contact pairs, area %+.2f %%, contact detection %.2f s (first s:interfaces() call, with its Lua tables)"):format(
  #big, found, count, 100 * (found_area - area) / area, seconds))
