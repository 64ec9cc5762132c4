-- The thesis's chapter 5 as assertions (Shin 2014, figures 12, 14, 15):
-- linear-elastic FEA with contact ties, iterative constraint relaxation,
-- and the comparison with equilibrium analysis.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local courses = require "ashlar.models.courses"
local support = require "spec_support"
local expect_error = support.expect_error

local NO_SLIDING = { friction = math.huge }

-- Figure 12: a semicircular arch with t/R = 0.12, one element per voussoir.
local function figure12_arch() return models.arch{ radius = 5, thickness = 0.6, voussoirs = 24 } end

-- Figure 14: a lintel on three posts, the left one thin, the middle one
-- thick, the right one in between, the middle post off centre.
local function figure14_posts()
  return models.post_and_lintel{ posts = { { width = 0.15 }, { width = 1.0 }, { width = 0.3 } },
                                 spans = { 2.85, 1.7 }, lintel = { 6, 0.5, 0.3 } }
end

-- Figure 15: a hemispherical dome with an oculus (the FEA needs hexahedra).
local function figure15_dome()
  return models.dome{ radius = 5, thickness = 0.5, meridians = 16, parallels = 8, oculus = 0.25 }
end

describe("ashlar.fea", function()
  it("gives every node a displacement, every element 8 nodes and the ties their forces", function()
    local s = models.column{ drums = 3 }
    local fe = ashlar.fea(s, { refine = 2, stresses = true })
    assert.is_nil(ashlar.fea(s).stresses)
    assert.are.equal("compression_only", fe.status)
    assert.is_true(fe.compression_only)
    assert.are.equal(0, fe.iterations)
    assert.are.equal(#fe.nodes, #fe.displacements)
    assert.are.equal(3 * 8, fe.element_count)
    assert.are.equal(fe.element_count, #fe.elements)
    assert.are.equal(fe.element_count, #fe.stresses)
    assert.are.equal(3 * #fe.nodes, fe.dofs)
    for _, e in ipairs(fe.elements) do assert.are.equal(8, #e) end
    -- The ground carries the whole weight: the contacts with it sum to it.
    local weight, carried = 0, 0
    for i = 1, #s do if not s:is_support(i) then weight = weight + s:block(i):mass() * 9.81 end end
    for _, f in ipairs(fe.interfaces) do
      if s:is_support(f.a) or s:is_support(f.b) then carried = carried + f.normal_force end
    end
    support.near(carried, weight, 1e-8 * weight, "ground reaction")
    support.near(fe.total_weight, weight, 1e-9 * weight)
    for _, c in ipairs(fe.contacts) do
      assert.is_false(c.released)
      assert.is_true(c.normal_force > -1e-9 * weight)
    end
    -- Compression everywhere: the bottom element's vertical stress is negative.
    assert.is_true(fe.stresses[1].zz < 0)
  end)

  it("gives the same answer with and without relaxation when every contact is in compression", function()
    local s = models.column{ drums = 4 }
    local relaxed, plain = ashlar.fea(s, { relax = true }), ashlar.fea(s, { relax = false })
    assert.are.equal(0, relaxed.iterations)
    for n, u in ipairs(plain.displacements) do
      for d = 1, 3 do assert.are.equal(u[d], relaxed.displacements[n][d]) end
    end
  end)

  it("finds tension at an arch's crown that equilibrium does not need, and relaxes it away (figure 12)", function()
    local s = figure12_arch()
    assert.is_true(ashlar.analyze(s, NO_SLIDING).stable)
    local tied = ashlar.fea(s, { relax = false })
    assert.are.equal("tension", tied.status)
    -- The crown joint's intrados (z = R - t/2 = 4.7) pulls apart.
    local crown = 0
    for _, c in ipairs(tied.contacts) do
      if c.tensile and math.abs(c.position[1]) < 1e-9 and math.abs(c.position[3] - 4.7) < 1e-9 then crown = crown + 1 end
    end
    assert.are.equal(2, crown)
    -- Opening one hinge at a time: compression-only after two iterations
    -- (the thesis: two).
    local relaxed = ashlar.fea(s, { method = "relaxation", release = "largest" })
    assert.are.equal("compression_only", relaxed.status)
    assert.are.equal(2, relaxed.iterations)
    assert.are.equal(3, #relaxed.history)
    assert.are.equal(0, relaxed.history[3].tensile)
    -- The thesis's rule, releasing every tensile node at once, opens the
    -- crown and both springings together: four hinges, a mechanism.
    local mechanism = ashlar.fea(s, { method = "relaxation" })
    assert.are.equal("mechanism", mechanism.status)
    -- Its last solve is no equilibrium: no displacement to report.
    assert.is_nil(mechanism.max_displacement)
    assert.is_nil(mechanism.max_penetration)
    assert.matches("^FeaResult %(mechanism after %d+ iterations%)$", tostring(mechanism))
    assert.is_true(relaxed.max_displacement > 0)
    -- Unilateral contact (the default) lets the springings close again:
    -- the arch stands, and its state is the relaxed one (three hinges'
    -- worth of open nodes: crown intrados, both haunches' extrados).
    local unilateral = ashlar.fea(s)
    assert.are.equal("compression_only", unilateral.status)
    assert.are.equal(0, unilateral.interior_point_iterations)
    local tolerance = 1e-6 * unilateral.total_weight / #unilateral.contacts  -- tension_tolerance's
    for _, c in ipairs(unilateral.contacts) do
      assert.is_true(c.normal_force >= -tolerance, "tension at a closed node")
      if c.released then
        assert.is_true(math.abs(c.normal_force) <= 1e-6 * tolerance, "force at an open node")
        assert.is_true(c.opening > -1e-6 * unilateral.max_displacement, "an open node overlaps")
      else
        assert.is_true(math.abs(c.opening) < 1e-9 * unilateral.max_displacement)
      end
    end
    assert.are.same(relaxed.released, unilateral.released)
    -- It got there by opening the springings with the crown, as the
    -- thesis's rule does, and closing them again.
    local closed_again = 0
    for _, h in ipairs(unilateral.history) do closed_again = closed_again + h.engaged end
    assert.is_true(closed_again > 0)
    -- With fewer voussoirs the thesis's rule suffices.
    local short = ashlar.fea(models.arch{ radius = 5, thickness = 0.6, voussoirs = 12 }, { method = "relaxation" })
    assert.are.equal("compression_only", short.status)
    assert.are.equal(1, short.iterations)
  end)

  it("finds the flying buttress standing, its reactions carrying its weight", function()
    local s = models.flying_buttress{}
    local fe = ashlar.fea(s)
    assert.are.equal("compression_only", fe.status)
    -- The active-set iteration cycles here; the interior-point program
    -- finds the contact state, which one more solve makes exact.
    assert.is_true(fe.interior_point_iterations > 0)
    local weight, vertical = 0, 0
    for i = 1, #s do if not s:is_support(i) then weight = weight + s:block(i):mass() * 9.81 end end
    for _, f in ipairs(fe.interfaces) do
      if s:is_support(f.a) then vertical = vertical + f.resultant[3]
      elseif s:is_support(f.b) then vertical = vertical - f.resultant[3] end
    end
    support.near(vertical, weight, 1e-8 * weight, "vertical reactions")
    -- Relaxation releases the flyer's hinges for good: a mechanism.
    assert.are.equal("mechanism", ashlar.fea(s, { method = "relaxation" }).status)
    local short = ashlar.fea(s, { max_relax_iterations = 3 })
    assert.are.equal("iteration_limit", short.status)
    assert.is_false(short.compression_only)
    assert.is_nil(short.max_displacement)
  end)

  it("finds tension under the lintel on the right post, and a hinge there once released (figure 14)", function()
    local s = figure14_posts()
    assert.is_true(ashlar.analyze(s).stable)
    local right = s:name(4) == "post right" and 4 or error("post order changed")
    local tied = ashlar.fea(s, { relax = false })
    assert.are.equal("tension", tied.status)
    for _, c in ipairs(tied.contacts) do
      if c.tensile then
        local f = tied.interfaces[c.interface]
        assert.is_true(f.a == right or f.b == right, "tension elsewhere than on the right post")
      end
    end
    assert.is_true(tied.interfaces[1].tension >= 0)
    local relaxed = ashlar.fea(s)
    assert.are.equal("compression_only", relaxed.status)
    assert.are.equal(1, relaxed.iterations)
    assert.are.equal(2, #relaxed.released)
    -- The released corner lifts off: the hinge, where nothing else opens.
    for _, k in ipairs(relaxed.released) do
      assert.is_true(relaxed.contacts[k].opening > 1e-3 * relaxed.max_displacement)
    end
    for _, c in ipairs(relaxed.contacts) do
      if not c.released then assert.is_true(math.abs(c.opening) < 1e-9 * relaxed.max_displacement) end
    end
    -- Finer elements along the lintel also pull at the edges of the other
    -- bonded contacts; relaxation still ends in compression.
    local fine = ashlar.fea(s, { element_size = 0.15 })
    assert.are.equal("compression_only", fine.status)
    assert.is_true(fine.iterations >= 1)
  end)

  it("puts more hoop force than equilibrium into a dome's bottom course (figure 15)", function()
    local s = figure15_dome()
    local r = ashlar.analyze(s)
    assert.is_true(r.stable)
    local fe = ashlar.fea(s)
    assert.are.equal("compression_only", fe.status)
    local eq, elastic = courses.hoop_ratios(s, r.interfaces), courses.hoop_ratios(s, fe.interfaces)
    assert.are.equal(8, #eq)
    -- Equilibrium: vertical at the bottom, hoops at the top.
    assert.is_true(eq[1] < 0.01)
    assert.is_true(eq[8] > 2)
    -- FEA: hoop force in the bottom course too, and at the top.
    assert.is_true(elastic[1] > 0.015)
    assert.is_true(elastic[8] > eq[8])
    -- Before relaxation the lower courses pull in hoop tension, as a
    -- hemispherical shell's membrane solution does below about 52 degrees.
    local tied = courses.hoop_ratios(s, ashlar.fea(s, { relax = false }).interfaces)
    assert.is_true(tied[3] < 0)
  end)

  it("writes the mesh with its results as VTU and the deformed shape as a 3D file", function()
    local dir = os.tmpname()
    os.remove(dir)
    assert(os.execute("mkdir -p " .. support.quote(dir)))
    local fe_structure = figure14_posts()
    local fe = ashlar.fea(fe_structure, { stresses = true })
    fe:export(dir .. "/posts.vtu")
    fe:export(dir .. "/posts.glb", { scale = 2000, undeformed = true })
    fe:export(dir .. "/posts_ascii.vtu", { format = "ascii" })
    local vtu = assert(io.open(dir .. "/posts.vtu", "rb")):read("a")
    local ascii = assert(io.open(dir .. "/posts_ascii.vtu", "rb")):read("a")
    -- The elements and one cell per support block (the ground).
    local supports = 0
    for i = 1, #fe_structure do if fe_structure:is_support(i) then supports = supports + 1 end end
    for _, text in ipairs{ vtu, ascii } do
      assert.is_truthy(text:find('NumberOfCells="' .. fe.element_count + supports .. '"', 1, true))
      assert.is_truthy(text:find('Name="displacement"', 1, true))
      assert.is_truthy(text:find('Name="nodal_stress"', 1, true))
    end
    -- Binary by default, compressed; ASCII on request.
    assert.is_truthy(vtu:find('compressor="vtkZLibDataCompressor"', 1, true))
    assert.is_truthy(vtu:find('<AppendedData encoding="raw">', 1, true))
    assert.is_falsy(ascii:find("AppendedData", 1, true))
    assert.is_true(#vtu < #ascii / 2)
    assert.is_truthy(io.open(dir .. "/posts.glb"))
    os.execute("rm -rf " .. support.quote(dir))
  end)

  it("rejects bad options and blocks that are not hexahedra", function()
    local s = models.column{ drums = 2 }
    expect_error({ "unknown option 'young_modulus'" }, ashlar.fea, s, { young_modulus = 1 })
    expect_error({ "refine: expected a whole number from 1 to 64" }, ashlar.fea, s, { refine = 0 })
    expect_error({ "poisson: expected a number in (-1, 0.5)" }, ashlar.fea, s, { poisson = 0.5 })
    expect_error({ "release: 'some' is not one of all, largest" }, ashlar.fea, s, { release = "some" })
    expect_error({ "method: 'lcp' is not one of unilateral, relaxation" }, ashlar.fea, s, { method = "lcp" })
    expect_error({ "young" }, ashlar.fea, s, { young = -1 })
    expect_error({ "is not a hexahedron", "oculus" }, ashlar.fea,
                 models.dome{ meridians = 8, parallels = 3 })
    local fe = ashlar.fea(s)
    expect_error({ "scale" }, function() fe:export(os.tmpname() .. ".vtu", { scale = 2 }) end)
    expect_error({ "format: 'text' is not one of binary, ascii" },
                 function() fe:export(os.tmpname() .. ".vtu", { format = "text" }) end)
    expect_error({ "format: applies to .vtu files" },
                 function() fe:export(os.tmpname() .. ".glb", { format = "ascii" }) end)
    expect_error({ "export_fea_mesh" }, function() fe:export(os.tmpname() .. ".glb", { color = "pink" }) end)
  end)
end)
