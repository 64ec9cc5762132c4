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
end)
