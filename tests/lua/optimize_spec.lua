-- ashlar.optimize: geometry and parameters moved down the structural
-- gradient until the structure stands (Shin 2014, figure 2), with the
-- constraints a designer sets.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

local NO_SLIDING = { friction = math.huge }

-- Below its minimum thickness (0.537 m for 24 voussoirs of R = 5 m).
local function thin_arch()
  return models.arch{ radius = 5, thickness = 0.4, voussoirs = 24 }
end

local function largest_move(before, after)
  local worst = 0
  for i = 1, #before do
    local a, b = before:block(i):vertices(), after:block(i):vertices()
    for k = 1, #a do
      for axis = 1, 3 do worst = math.max(worst, math.abs(a[k][axis] - b[k][axis])) end
    end
  end
  return worst
end

describe("ashlar.optimize", function()
  it("makes an unstable arch stable; L-BFGS in fewer iterations (figure 2)", function()
    local arch = thin_arch()
    assert.is_false(ashlar.analyze(arch, NO_SLIDING).stable)
    local iterations = {}
    for _, method in ipairs{ "gradient", "lbfgs" } do
      local r = ashlar.optimize(arch, { method = method, analysis = NO_SLIDING, initial_step = 0.01,
                                        symmetry = { point = { 0, 0, 0 }, normal = { 1, 0, 0 } },
                                        progress = false })
      assert.is_true(r.stable, method .. ": " .. r.message)
      assert.are.equal("stable", r.status)
      assert.is_true(ashlar.analyze(r.structure, NO_SLIDING).stable)
      local history = r.history
      assert.are.equal(0, history[1].iteration)
      near(history[1].infeasibility, ashlar.analyze(arch, NO_SLIDING).infeasibility, 1e-9)
      for k = 2, #history do
        assert.is_true(history[k].penalty < history[k - 1].penalty, method .. " descends")
      end
      assert.are.equal(0, history[#history].infeasibility)
      iterations[method] = history[#history].iteration
      -- Supports stay; the arch stays symmetric about x = 0.
      for i = 1, #arch do
        if arch:is_support(i) then assert.are.same(arch:block(i):vertices(), r.structure:block(i):vertices()) end
      end
      local left, right = r.structure:block(1):vertices(), r.structure:block(24):vertices()
      local xs_left, xs_right = {}, {}
      for k = 1, #left do xs_left[#xs_left + 1] = -left[k][1]; xs_right[#xs_right + 1] = right[k][1] end
      table.sort(xs_left)
      table.sort(xs_right)
      for k = 1, #xs_left do near(xs_left[k], xs_right[k], 1e-9) end
    end
    assert.is_true(iterations.gradient <= 6 and iterations.lbfgs <= 6)
    assert.is_true(iterations.lbfgs < iterations.gradient)
  end)

  it("keeps fixed blocks, predicates, name patterns and displacement bounds", function()
    local arch = thin_arch()
    local r = ashlar.optimize(arch, { analysis = NO_SLIDING, fixed = { "voussoir 12" },
                                      fixed_names = "^voussoir 1$",
                                      fixed_vertices = function(p) return p[3] > 4.9 end,
                                      max_displacement = 0.05, max_iterations = 3, progress = false })
    for _, name in ipairs{ "voussoir 12", "voussoir 1" } do
      local i = arch:find(name)
      assert.are.same(arch:block(i):vertices(), r.structure:block(i):vertices())
    end
    for i = 1, #arch do
      local before, after = arch:block(i):vertices(), r.structure:block(i):vertices()
      for k = 1, #before do
        if before[k][3] > 4.9 then assert.are.same(before[k], after[k]) end
      end
    end
    assert.is_true(largest_move(arch, r.structure) <= 0.05 + 1e-9)
    assert.is_true(largest_move(arch, r.structure) > 0)
  end)

  it("holds springings on their supports, or lets them slide in the support's plane", function()
    local arch = thin_arch()
    local function springing(structure)  -- voussoir 1's vertices on the support's top, z = 0
      local points = {}
      for _, p in ipairs(structure:block(1):vertices()) do
        if math.abs(p[3]) < 1e-9 then points[#points + 1] = p end
      end
      return points
    end
    local options = { analysis = NO_SLIDING, symmetry = { point = { 0, 0, 0 }, normal = { 1, 0, 0 } },
                      progress = false }
    local held = ashlar.optimize(arch, options)
    assert.is_true(held.stable, held.message)
    assert.are.same(springing(arch), springing(held.structure))
    options.slide_on_fixed = true
    local slid = ashlar.optimize(arch, options)
    assert.is_true(slid.stable, slid.message)
    local before, after = springing(arch), springing(slid.structure)
    assert.are.equal(#before, #after)  -- still on the support's plane
    local moved = 0
    for k = 1, #before do
      for axis = 1, 3 do moved = math.max(moved, math.abs(after[k][axis] - before[k][axis])) end
    end
    assert.is_true(moved > 1e-3, "the springing moves along the support: " .. moved)
    assert.is_true(ashlar.analyze(slid.structure, NO_SLIDING).stable)
  end)

  it("optimises a generator's parameters to the minimum thickness", function()
    local function arch_of(p) return models.arch{ radius = 5, thickness = p.thickness, voussoirs = 24 } end
    local r = ashlar.optimize(arch_of, { params = { thickness = 0.4 }, lower = { thickness = 0.2 },
                                         upper = { thickness = 1.0 }, analysis = NO_SLIDING, progress = false })
    assert.is_true(r.stable, r.message)
    local minimum = support.threshold(function(t)
      return ashlar.analyze(arch_of{ thickness = t }, NO_SLIDING).stable
    end, 0.4, 0.7, 1e-5)
    assert.is_true(r.params.thickness >= minimum - 1e-4, ("%g below the minimum %g"):format(r.params.thickness, minimum))
    assert.is_true(r.params.thickness <= 1.0)
    assert.is_true(ashlar.analyze(r.structure, NO_SLIDING).stable)
  end)

  it("stops with a status, not an error, when it cannot reach stable", function()
    local r = ashlar.optimize(thin_arch(), { analysis = NO_SLIDING, max_iterations = 1, initial_step = 1e-4,
                                             progress = false })
    assert.is_false(r.stable)
    assert.are.equal("max_iterations", r.status)
    assert.are.equal(2, #r.history)
  end)

  it("rejects bad options with clear messages", function()
    local arch = thin_arch()
    expect_error({ "method: 'newton' is not one of lbfgs, gradient" }, ashlar.optimize, arch, { method = "newton" })
    expect_error({ "keep_normal[1].face: 9 is out of range (block 1 has 6 faces)" },
      ashlar.optimize, arch, { keep_normal = { { block = 1, face = 9 } } })
    expect_error({ "fixed[1]: no block is named 'keystone'" }, ashlar.optimize, arch, { fixed = { "keystone" } })
    expect_error({ "unknown option 'analysis.frction'" }, ashlar.optimize, arch, { analysis = { frction = 1 } })
    expect_error({ "params: required" }, ashlar.optimize, function() return arch end, {})
    -- A parameter that changes the topology ends the run with that reason.
    local r = ashlar.optimize(
      function(p) return models.arch{ radius = 5, thickness = 0.4, voussoirs = math.floor(p.voussoirs + 0.5) } end,
      { params = { voussoirs = 24.5 }, progress = false })
    assert.are.equal("evaluation_failed", r.status)
    assert.truthy(r.message:find("parameter 'voussoirs' changes the number of blocks", 1, true), r.message)
  end)
  -- Optimisation to a margin: the least material whose margin reaches a
  -- target, against bisections over ashlar.analyze's verdict (and
  -- ashlar.load_factor) in the test itself.
  local function arch16(p) return models.arch{ radius = 5, thickness = p.t, voussoirs = 16 } end
  -- A point load of 20 kN straight down at the centroid of the voussoir
  -- nearest the quarter span (x = -2.5 m).
  local function loaded16(p)
    local s = arch16(p)
    local nearest, distance
    for i = 1, #s do
      if not s:is_support(i) then
        local d = math.abs(s:block(i):centroid()[1] + 2.5)
        if not distance or d < distance then nearest, distance = i, d end
      end
    end
    s:add_load{ block = nearest, force = { 0, 0, -2e4 }, at = s:block(nearest):centroid() }
    return s
  end
  local function bisection_minimum(model)
    return support.threshold(function(t) return ashlar.analyze(model{ t = t }, NO_SLIDING).stable end,
      0.3, 1.2, 1e-5)
  end

  it("minimises volume to the bisection minimum thickness, from either side, unloaded and loaded", function()
    local minimum = bisection_minimum(arch16)
    -- The polyhedral 16-voussoir arch's minimum (DESIGN.md): t/R = 0.10708.
    near(minimum / 5, 0.10708, 2e-5, "bisection")
    for _, case in ipairs{ { arch16, minimum }, { loaded16, bisection_minimum(loaded16) } } do
      local model, reference = case[1], case[2]
      for _, start in ipairs{ 0.4, 1.1 } do
        local r = ashlar.optimize(model, { params = { t = start }, lower = { t = 0.2 }, upper = { t = 1.2 },
                                           objective = "volume", analysis = NO_SLIDING, progress = false })
        assert.are.equal("converged", r.status, r.message)
        assert.is_true(r.stable and r.on_boundary)
        assert.are.same({}, r.active_bounds)
        -- Stated tolerance: within bracket_tolerance (1e-3) x (upper - lower) above the boundary.
        assert.is_true(r.params.t >= reference - 1e-5 and r.params.t <= reference + 1e-3 + 1e-5,
          ("from %g: %.6f against the bisection's %.6f"):format(start, r.params.t, reference))
        assert.is_true(ashlar.analyze(r.structure, NO_SLIDING).stable)
        near(r.value, support.free_volume(r.structure), 1e-12, "value is the free blocks' volume")
        for k = 2, #r.history do  -- once the target is reached the volume only falls
          if r.history[k - 1].stable then assert.is_true(r.history[k].value < r.history[k - 1].value) end
        end
      end
    end
    assert.is_true(bisection_minimum(loaded16) > minimum + 0.03)  -- the load matters
  end)

  it("reaches a load factor target with the least thickness, and a geometric factor", function()
    local target = 0.1
    local r = ashlar.optimize(arch16, { params = { t = 0.9 }, lower = { t = 0.2 }, upper = { t = 1.2 },
                                        target = { load_factor = target }, analysis = NO_SLIDING, progress = false })
    assert.are.equal("converged", r.status, r.message)
    local factor = ashlar.load_factor(r.structure, NO_SLIDING).factor
    near(r.margin, factor, 1e-12, "margin")
    -- At least the target, and above it by no more than the factor's slope
    -- (about 0.7 per metre here) times the bracket (1e-3 m).
    assert.is_true(factor >= target and factor <= target + 1e-3, "load factor " .. factor)
    assert.is_true(ashlar.load_factor(arch16{ t = r.params.t - 2e-3 }, NO_SLIDING).factor < target)
    -- A geometric factor of 1.5: 1.5 times the least thickness that stands.
    local g = ashlar.optimize(arch16, { params = { t = 0.6 }, lower = { t = 0.2 }, upper = { t = 1.2 },
                                        objective = "weight", target = { geometric_factor = 1.5 },
                                        analysis = NO_SLIDING, progress = false })
    assert.are.equal("converged", g.status, g.message)
    assert.are.equal("weight", g.objective)
    near(g.params.t / 1.5, 5 * 0.10708, 1e-3 / 1.5 + 1e-4, "geometric factor")
  end)

  it("reports the bounds that end a run, with status at_bound", function()
    -- The least thickness that stands lies below the lower bound: at_bound, standing.
    local low = ashlar.optimize(arch16, { params = { t = 0.9 }, lower = { t = 0.7 }, upper = { t = 1.2 },
                                          objective = "volume", analysis = NO_SLIDING, progress = false })
    assert.are.equal("at_bound", low.status, low.message)
    assert.is_true(low.stable)
    assert.are.same({ t = "lower" }, low.active_bounds)
    assert.are.equal(0.7, low.params.t)
    -- Nothing up to the upper bound stands: at_bound, not stable, with and without a target.
    for _, options in ipairs{ { objective = "volume" }, {} } do
      options.params, options.lower, options.upper = { t = 0.3 }, { t = 0.2 }, { t = 0.5 }
      options.analysis, options.progress = NO_SLIDING, false
      local high = ashlar.optimize(arch16, options)
      assert.are.equal("at_bound", high.status, high.message)
      assert.is_false(high.stable)
      assert.are.same({ t = "upper" }, high.active_bounds)
      assert.are.equal(0.5, high.params.t)
    end
  end)

  it("rejects bad targets with clear messages", function()
    local base = { params = { t = 0.6 }, progress = false }
    local function with(extra)
      local options = {}
      for k, v in pairs(base) do options[k] = v end
      for k, v in pairs(extra) do options[k] = v end
      return options
    end
    expect_error({ "target: give exactly one of stable = true, load_factor = f, geometric_factor = g; got 2" },
      ashlar.optimize, arch16, with{ target = { stable = true, load_factor = 0.1 } })
    expect_error({ "method: not with a target" }, ashlar.optimize, arch16, with{ target = { stable = true }, method = "lbfgs" })
    expect_error({ "objective: 'mass' is not one of volume, weight" }, ashlar.optimize, arch16, with{ objective = "mass" })
    expect_error({ "target.direction: only with target.load_factor" },
      ashlar.optimize, arch16, with{ target = { stable = true, direction = { 1, 0, 0 } } })
    expect_error({ "target.parameter: 'r' is not one of params" },
      ashlar.optimize, arch16, with{ target = { geometric_factor = 1.5, parameter = "r" } })
    expect_error({ "bracket_tolerance must be in (0, 1), got 2" },
      ashlar.optimize, arch16, with{ objective = "volume", bracket_tolerance = 2 })
    expect_error({ "bracket_tolerance: only with a target" }, ashlar.optimize, arch16, with{ bracket_tolerance = 0.01 })
  end)
  it("minimises a standing arch's volume over its vertices, with a smooth intrados and a minimum thickness", function()
    local arch = models.arch{ radius = 5, thickness = 0.8, voussoirs = 12 }
    -- The intrados at the front face: one position per joint, in order of angle.
    local ymin = math.huge
    for i = 1, #arch do for _, p in ipairs(arch:block(i):vertices()) do ymin = math.min(ymin, p[2]) end end
    local curve, seen = {}, {}
    for i = 1, #arch do
      if not arch:is_support(i) then
        for k, p in ipairs(arch:block(i):vertices()) do
          local key = ("%.9f %.9f"):format(p[1], p[3])
          if math.abs(p[2] - ymin) < 1e-9 and math.sqrt(p[1] ^ 2 + p[3] ^ 2) < 5 and not seen[key] then
            seen[key] = true
            curve[#curve + 1] = { block = i, vertex = k, angle = math.atan(p[3], p[1]) }
          end
        end
      end
    end
    table.sort(curve, function(a, b) return a.angle < b.angle end)
    for _, ref in ipairs(curve) do ref.angle = nil end
    assert.are.equal(13, #curve)
    local function at(s, ref) return s:block(ref.block):vertices()[ref.vertex] end
    local function roughness(s)  -- the sum of squared second differences (m^2)
      local sum = 0
      for k = 2, #curve - 1 do
        local a, b, c = at(s, curve[k - 1]), at(s, curve[k]), at(s, curve[k + 1])
        for axis = 1, 3 do sum = sum + (a[axis] - 2 * b[axis] + c[axis]) ^ 2 end
      end
      return sum
    end
    local function volume(s)
      local sum = 0
      for i = 1, #s do if not s:is_support(i) then sum = sum + s:block(i):volume() end end
      return sum
    end
    local function least_width(s)  -- of the contact polygons: least over edges of the farthest vertex
      local least = math.huge
      for _, f in ipairs(s:interfaces()) do
        local p, n = f.vertices, f.normal
        for e = 1, #p do
          local q = p[e % #p + 1]
          local edge = { q[1] - p[e][1], q[2] - p[e][2], q[3] - p[e][3] }
          local across = { n[2] * edge[3] - n[3] * edge[2], n[3] * edge[1] - n[1] * edge[3], n[1] * edge[2] - n[2] * edge[1] }
          local length = math.sqrt(across[1] ^ 2 + across[2] ^ 2 + across[3] ^ 2)
          local farthest = 0
          for _, r in ipairs(p) do
            local d = ((r[1] - p[e][1]) * across[1] + (r[2] - p[e][2]) * across[2] + (r[3] - p[e][3]) * across[3]) / length
            farthest = math.max(farthest, math.abs(d))
          end
          least = math.min(least, farthest)
        end
      end
      return least
    end
    local function optimized(extra)
      local options = { objective = "volume", analysis = NO_SLIDING, max_iterations = 10, progress = false,
                        symmetry = { point = { 0, 0, 0 }, normal = { 1, 0, 0 } } }
      for k, v in pairs(extra) do options[k] = v end
      local r = ashlar.optimize(arch, options)
      assert.is_true(r.stable, r.message)
      assert.is_true(ashlar.analyze(r.structure, NO_SLIDING).stable)
      -- The objective: the volume, plus the smoothing weight times the roughness.
      near(r.value, volume(r.structure) + (extra.smooth and extra.smooth.weight * roughness(r.structure) or 0), 1e-9,
        "value")
      return r
    end
    assert.is_true(ashlar.analyze(arch, NO_SLIDING).stable)  -- it stands as built: no first-stable stop
    local plain = optimized{}
    assert.is_true(volume(plain.structure) < 0.5 * volume(arch), "volume " .. volume(plain.structure))
    for k = 2, #plain.history do assert.is_true(plain.history[k].value < plain.history[k - 1].value) end
    local smooth = optimized{ smooth = { weight = 10, curves = { curve } } }
    assert.is_true(roughness(smooth.structure) < 0.6 * roughness(plain.structure),
      ("smoothed %g against %g"):format(roughness(smooth.structure), roughness(plain.structure)))
    assert.is_true(volume(smooth.structure) < volume(arch))
    assert.is_true(least_width(plain.structure) < 0.6)
    local thick = optimized{ min_thickness = 0.6 }
    assert.is_true(least_width(thick.structure) >= 0.6 - 1e-9, "least width " .. least_width(thick.structure))
    assert.is_true(volume(thick.structure) < volume(arch))
    expect_error({ "target: a structure's vertices are optimised to stable = true only" },
      ashlar.optimize, arch, { target = { load_factor = 0.1 } })
    expect_error({ "min_thickness: only with objective" }, ashlar.optimize, arch, { min_thickness = 0.5 })
    expect_error({ "min_thickness: the structure's narrowest joint is 0.8" },
      ashlar.optimize, arch, { objective = "volume", min_thickness = 0.9, progress = false })
  end)
end)
