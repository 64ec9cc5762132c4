-- ashlar.gradient against central finite differences of re-analysed
-- structures. Moves keep every face planar (blocks are re-validated), keep
-- coincident vertices together (contacts stay closed) and change no active
-- set, so the closed-form gradient must match to 1e-4.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"

local TOLERANCE = 1e-4

-- `s` with block vertices `vertices[i]` and cable points `cables[c]`.
local function rebuilt(s, vertices, cables)
  local t = ashlar.structure()
  for i = 1, #s do
    local b = s:block(i)
    t:add(ashlar.block{ vertices = vertices[i], faces = b:faces(), density = b:density() },
      { support = s:is_support(i), name = s:name(i) })
  end
  t:set_planar(s:is_planar())
  for _, load in ipairs(s:loads()) do t:add_load(load) end
  for c, cable in ipairs(s:cables()) do
    local points = cables and cables[c] or cable
    t:add_cable{ from = { block = cable.from.block, point = points.from.point },
                 to = { block = cable.to.block, point = points.to.point },
                 mass_per_length = cable.mass_per_length, max_tension = cable.max_tension }
  end
  return t
end

-- Vertices grouped by position (`key` of a point); each group moves as one.
local function groups_of(s, key)
  local groups, by_key = {}, {}
  for i = 1, #s do
    for k, p in ipairs(s:block(i):vertices()) do
      local name = key(p)
      if not by_key[name] then
        by_key[name] = {}
        groups[#groups + 1] = by_key[name]
      end
      table.insert(by_key[name], { i, k })
    end
  end
  return groups
end

local function exact_key(p) return ("%.9f %.9f %.9f"):format(p[1], p[2], p[3]) end
-- In a planar structure the vertices on one line along y move together in x
-- and z: every face then stays planar.
local function extrusion_key(p) return ("%.9f %.9f"):format(p[1], p[3]) end

-- Vertices displaced by h * direction[group] for every group.
local function displaced(s, groups, directions, h)
  local vertices = {}
  for i = 1, #s do vertices[i] = s:block(i):vertices() end
  for gi, group in ipairs(groups) do
    for _, member in ipairs(group) do
      local p = vertices[member[1]][member[2]]
      for axis = 1, 3 do p[axis] = p[axis] + h * directions[gi][axis] end
    end
  end
  return vertices
end

local function directional_analytic(g, groups, directions)
  local sum = 0
  for gi, group in ipairs(groups) do
    for _, member in ipairs(group) do
      for axis = 1, 3 do sum = sum + g[member[1]][member[2]][axis] * directions[gi][axis] end
    end
  end
  return sum
end

local function central_difference(s, options, groups, directions, h)
  local plus = ashlar.analyze(rebuilt(s, displaced(s, groups, directions, h)), options)
  local minus = ashlar.analyze(rebuilt(s, displaced(s, groups, directions, -h)), options)
  return (plus.penalty - minus.penalty) / (2 * h)
end

-- Every group, along x and z, one at a time (planar structures). Returns the
-- worst relative error.
local function check_each_group(s, options, h)
  local g = ashlar.gradient(s, options)
  assert.is_true(g.valid)
  assert.is_false(g.stable)
  local groups = groups_of(s, extrusion_key)
  local worst, scale = 0, 0
  for _, group in ipairs(groups) do
    for _, axis in ipairs{ 1, 3 } do
      local v = g[group[1][1]][group[1][2]][axis]
      scale = math.max(scale, math.abs(v))
    end
  end
  for gi = 1, #groups do
    for _, axis in ipairs{ 1, 3 } do
      local directions = {}
      for j = 1, #groups do directions[j] = { 0, 0, 0 } end
      directions[gi][axis] = 1
      local analytic = directional_analytic(g, groups, directions)
      local numeric = central_difference(s, options, groups, directions, h)
      -- Relative to the largest component: entries near zero are compared
      -- at the gradient's own scale.
      worst = math.max(worst, math.abs(analytic - numeric) / math.max(math.abs(numeric), 0.01 * scale))
    end
  end
  return worst
end

-- Directional derivatives along random moves of the coincident-vertex groups
-- (3D structures), small enough to keep faces planar within validation.
local function check_random_directions(s, options, h, count)
  local g = ashlar.gradient(s, options)
  assert.is_true(g.valid)
  assert.is_false(g.stable)
  local groups = groups_of(s, exact_key)
  local random = 12345
  local function uniform()
    random = (random * 1103515245 + 12345) % 2147483648
    return random / 2147483648 * 2 - 1
  end
  local worst = 0
  for _ = 1, count do
    local directions = {}
    for j = 1, #groups do directions[j] = { uniform(), uniform(), uniform() } end
    local analytic = directional_analytic(g, groups, directions)
    local numeric = central_difference(s, options, groups, directions, h)
    worst = math.max(worst, math.abs(analytic - numeric) / math.abs(numeric))
  end
  return worst
end

describe("ashlar.gradient", function()
  it("matches finite differences on a thin arch, with and without sliding", function()
    local arch = models.arch{ radius = 5, thickness = 0.3, voussoirs = 12 }
    local worst = check_each_group(arch, { friction = math.huge, tolerance = 1e-12 }, 1e-6)
    assert.is_true(worst <= TOLERANCE, "worst relative error " .. worst)
    worst = check_each_group(arch, { friction = 0.4, tolerance = 1e-12 }, 1e-6)
    assert.is_true(worst <= TOLERANCE, "worst relative error " .. worst)
  end)

  it("matches finite differences on a wall pushed sideways", function()
    local wall = models.wall{ length = 3, height = 2, brick = { 1, 0.5 }, thickness = 0.4, bond = "stack" }
    wall:add_load{ block = #wall, force = { 2e4, 0, 0 } }
    local worst = check_each_group(wall, { friction = math.huge, tolerance = 1e-13 }, 2e-7)
    assert.is_true(worst <= TOLERANCE, "worst relative error " .. worst)
  end)

  it("matches finite differences on a thin dome", function()
    local dome = models.dome{ radius = 5, thickness = 0.15, meridians = 8, parallels = 5 }
    local worst = check_random_directions(dome, { friction = math.huge, tolerance = 1e-13 }, 2e-7, 4)
    assert.is_true(worst <= TOLERANCE, "worst relative error " .. worst)
  end)

  it("matches finite differences on a cable structure, cable ends included", function()
    -- A beam overhanging its pier, held by an inclined cable whose pull is
    -- capped, so it needs tension at the pier too.
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 1.3, 1 }, center = { 0, 0, 0.5 } }, { support = true })
    s:add(ashlar.box{ size = { 4, 0.8, 0.5 }, center = { 1.2, 0, 1.25 } })
    s:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { 0, 0, 4.1 } }, { support = true })
    s:add_cable{ from = { block = 2, point = { 2.5, 0.3, 1.5 } }, to = { block = 3, point = { 0.2, 0.1, 4 } },
                 mass_per_length = 50, max_tension = 1e4 }
    local options = { friction = math.huge, tolerance = 1e-13 }
    local worst = check_random_directions(s, options, 2e-7, 4)
    assert.is_true(worst <= TOLERANCE, "worst relative error " .. worst)
    local g = ashlar.gradient(s, options)
    local cable = s:cables()[1]
    local h = 1e-6
    for _, end_name in ipairs{ "from", "to" } do
      for axis = 1, 3 do
        local function penalty_at(e)
          local points = { from = { point = { table.unpack(cable.from.point) } },
                           to = { point = { table.unpack(cable.to.point) } } }
          points[end_name].point[axis] = points[end_name].point[axis] + e
          local vertices = {}
          for i = 1, #s do vertices[i] = s:block(i):vertices() end
          return ashlar.analyze(rebuilt(s, vertices, { points }), options).penalty
        end
        local numeric = (penalty_at(h) - penalty_at(-h)) / (2 * h)
        support.near(g.cables[1][end_name][axis], numeric, TOLERANCE * math.max(math.abs(numeric), 1e-3),
          "cable " .. end_name .. " axis " .. axis)
      end
    end
  end)

  it("reports its time and the analysis' (timing is measured by scripts, never asserted)", function()
    local arch = models.arch{ radius = 5, thickness = 0.3, voussoirs = 64 }
    local g = ashlar.gradient(arch, { friction = math.huge })
    assert.is_true(g.seconds > 0 and g.analysis_seconds > 0)
    assert.are.equal(#arch, #g)
    assert.are.equal(#arch:block(2):vertices(), #g[2])
  end)
end)
