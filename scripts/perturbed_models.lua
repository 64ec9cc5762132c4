-- Imperfect models, as CAD and scans deliver them: every vertex of every
-- free block of a generated barrel vault and dome moved at random by up to
-- 1 % of its block's size (warped faces, gaps and overlaps of that order),
-- written to OBJ and imported back with `planarity`, then compared with the
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
math.randomseed(20261126)

local function block_size(b)
  local lo, hi = b:bounds()
  return math.sqrt((hi[1] - lo[1]) ^ 2 + (hi[2] - lo[2]) ^ 2 + (hi[3] - lo[3]) ^ 2)
end

-- A random vector of length up to `length`, uniform in the ball.
local function random_move(length)
  while true do
    local v = { 2 * math.random() - 1, 2 * math.random() - 1, 2 * math.random() - 1 }
    local r2 = v[1] ^ 2 + v[2] ^ 2 + v[3] ^ 2
    if r2 <= 1 and r2 > 0 then
      for k = 1, 3 do v[k] = v[k] * length end
      return v
    end
  end
end

-- The model with its free blocks' vertices moved, through an OBJ file; the
-- supports keep their names and are picked by them on import.
local function perturbed_through_obj(s, name)
  local moved = ashlar.structure()
  local supports, sizes = {}, 0
  for i = 1, #s do
    local b = s:block(i)
    local size = block_size(b)
    sizes = sizes + size
    local vertices = b:vertices()
    if s:is_support(i) then
      supports[s:name(i)] = true
    else
      for _, p in ipairs(vertices) do
        local d = random_move(AMOUNT * size)
        for k = 1, 3 do p[k] = p[k] + d[k] end
      end
    end
    moved:add(ashlar.block{ vertices = vertices, faces = b:faces(), planarity = PLANARITY, name = s:name(i) },
      { support = s:is_support(i), name = s:name(i) })
  end
  local path = ("%s/perturbed_%s.obj"):format(folder, name)
  ashlar.export(moved, path)
  local imported = ashlar.import(path, { planarity = PLANARITY, support = function(n) return supports[n] == true end })
  return imported, sizes / #s
end

-- Pairs of blocks in contact (the OBJ file's faces are triangles, so one
-- joint may come back as several interfaces), and the total contact area.
local function interfaces_of(s, tolerance)
  local list = s:interfaces{ tolerance = tolerance }
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
print(("%-22s %6s %11s %11s %8s %8s %8s %9s"):format("model", "blocks", "pairs", "area m^2", "area %",
  "stable", "before", "tolerance"))
local cases = {
  { "barrel vault t/R 0.15", models.barrel_vault{ radius = 3, thickness = 0.45, voussoirs = 24, courses = 6, bond = "running" } },
  { "barrel vault t/R 0.09", models.barrel_vault{ radius = 3, thickness = 0.27, voussoirs = 24, courses = 6, bond = "running" } },
  { "dome t/R 0.1", models.dome{ radius = 5, thickness = 0.5 } },
  { "dome t/R 0.02", models.dome{ radius = 5, thickness = 0.1 } },
}
for index, case in ipairs(cases) do
  local name, s = case[1], case[2]
  local count, area = interfaces_of(s)
  local before = ashlar.analyze(s, { friction = FRICTION })
  local p, mean_size = perturbed_through_obj(s, tostring(index))
  local tolerance = TOLERANCE * AMOUNT * mean_size
  local found, found_area = interfaces_of(p, tolerance)
  local ok, r = pcall(ashlar.analyze, p, { friction = FRICTION, contact_tolerance = tolerance })
  print(("%-22s %6d %5d/%-5d %5.2f/%-5.2f %+7.2f %8s %8s %9.4f"):format(name, #s, found, count, found_area, area,
    100 * (found_area - area) / area, ok and tostring(r.stable) or "error", tostring(before.stable), tolerance))
  if not ok then print("  " .. tostring(r)) end
end

-- Contact detection at scale: a 10,027-block vault, perturbed in memory.
local big = models.barrel_vault{ radius = 2, thickness = 0.4, voussoirs = 50, courses = 200, length = 50, bond = "running" }
local moved, sizes = ashlar.structure(), 0
for i = 1, #big do
  local b = big:block(i)
  local size = block_size(b)
  sizes = sizes + size
  local vertices = b:vertices()
  if not big:is_support(i) then
    for _, p in ipairs(vertices) do
      local d = random_move(AMOUNT * size)
      for k = 1, 3 do p[k] = p[k] + d[k] end
    end
  end
  moved:add(ashlar.block{ vertices = vertices, faces = b:faces(), planarity = PLANARITY }, { support = big:is_support(i) })
end
local tolerance = TOLERANCE * AMOUNT * sizes / #big
local t0 = ashlar.clock()
local found, found_area = interfaces_of(moved, tolerance)
local seconds = ashlar.clock() - t0
local count, area = interfaces_of(big)
print(("%d-block vault: %d of %d contact pairs, area %+.2f %%, contact detection %.2f s (first s:interfaces() call, with its Lua tables)"):format(
  #big, found, count, 100 * (found_area - area) / area, seconds))
