-- Cables (tension-only elements, Shin 2014 "Extension to tension elements"):
-- tensions against statics worked by hand, virtual torques when axial forces
-- cannot balance a block (figure 1), junctions, bounds, files and errors.
local ashlar = require "ashlar"
local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

local g = 9.81
local block_weight = 2400 * g  -- a 1 m cube of the default density

-- A 1 m cube hanging from a fixed beam; the cable is attached at `offset` (m)
-- along x from the top face's centre.
local function hanging_cube(offset, cable)
  local s = ashlar.structure()
  local beam = s:add(ashlar.box{ size = { 4, 1, 0.5 }, center = { 0, 0, 5 } }, { support = true })
  local cube = s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 2 } })
  cable = cable or {}
  cable.from = { block = cube, point = { offset, 0, 2.5 } }
  cable.to = { block = beam, point = { offset, 0, 4.75 } }
  s:add_cable(cable)
  return s
end

describe("cables", function()
  it("carry a hanging block's weight plus half their own", function()
    local r = ashlar.analyze(hanging_cube(0, { mass_per_length = 10 }))
    assert.is_true(r.stable)
    assert.are.equal(0, r.infeasibility)
    -- 2.25 m of 10 kg/m: half of it hangs on the block's end.
    near(r.cables[1].tension, block_weight + 10 * 2.25 * g / 2, 1e-6 * block_weight)
    near(r.cables[1].compression, 0, 1e-6 * block_weight)
  end)

  it("need virtual torques where axial forces cannot balance a block", function()
    local r = ashlar.analyze(hanging_cube(0.5))
    assert.is_false(r.stable)
    near(r.cables[1].tension, block_weight, 1e-6 * block_weight)
    -- The weight acts 0.5 m from the cable: a torque W e about y.
    local torque = r.blocks[2].virtual_torque
    near(torque[2], block_weight * 0.5, 1e-6 * block_weight)
    near(torque[1], 0, 1e-6 * block_weight)
    -- Infeasibility: the torque over the weight times the unit of length
    -- (the cube's diagonal, sqrt 3 m), per analysed body.
    near(r.infeasibility, 0.5 / math.sqrt(3), 1e-6)
    assert.is_true(r.penalty > r.infeasibility)
  end)

  it("meet at junctions: a V of two cables holding a third", function()
    local s = ashlar.structure()
    local beam = s:add(ashlar.box{ size = { 4, 1, 0.5 }, center = { 0, 0, 5 } }, { support = true })
    local cube = s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 1 } })
    s:add_cable{ from = { point = { 0, 0, 3 } }, to = { block = beam, point = { -1.5, 0, 4.75 } } }
    s:add_cable{ from = { point = { 0, 0, 3 } }, to = { block = beam, point = { 1.5, 0, 4.75 } } }
    s:add_cable{ from = { block = cube, point = { 0, 0, 1.5 } }, to = { point = { 0, 0, 3 } } }
    local r = ashlar.analyze(s)
    assert.is_true(r.stable)
    local cosine = 1.75 / math.sqrt(1.5 ^ 2 + 1.75 ^ 2)
    near(r.cables[3].tension, block_weight, 1e-6 * block_weight)
    near(r.cables[1].tension, block_weight / (2 * cosine), 1e-6 * block_weight)
    near(r.cables[2].tension, block_weight / (2 * cosine), 1e-6 * block_weight)
  end)

  it("resist no compression: a cable under a block cannot prop it", function()
    -- A cube on a cable from the ground below: only a push would hold it, and
    -- virtual torques give no force.
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "ground" })
    s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 2 } }, { name = "cube" })
    s:add_cable{ from = { block = "cube", point = { 0, 0, 1.5 } }, to = { block = "ground", point = { 0, 0, 0 } } }
    local r = ashlar.analyze(s)
    assert.is_false(r.stable)
    near(r.cables[1].compression, block_weight, 1e-6 * block_weight)
    near(r.cables[1].tension, -block_weight, 1e-6 * block_weight)
    near(r.infeasibility, 1, 1e-6)
    -- A beam overhanging its pier: a cable from above holds it up.
    local s2 = ashlar.structure()
    s2:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 0.5 } }, { support = true })
    s2:add(ashlar.box{ size = { 4, 1, 0.5 }, center = { 1, 0, 1.25 } })
    s2:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { 2.5, 0, 3.1 } }, { support = true })
    s2:add_cable{ from = { block = 2, point = { 2.5, 0, 1.5 } }, to = { block = 3, point = { 2.5, 0, 3 } } }
    local r2 = ashlar.analyze(s2, { friction = math.huge })
    assert.is_true(r2.stable)
    assert.is_true(r2.cables[1].tension > 0)
  end)

  it("keep to max_tension", function()
    -- Two vertical cables share a centred hanging cube; one is limited to a
    -- quarter of the weight, so the other carries the rest.
    local s = ashlar.structure()
    local beam = s:add(ashlar.box{ size = { 4, 1, 0.5 }, center = { 0, 0, 5 } }, { support = true })
    local cube = s:add(ashlar.box{ size = { 1, 1, 1 }, center = { 0, 0, 2 } })
    s:add_cable{ from = { block = cube, point = { -0.25, 0, 2.5 } }, to = { block = beam, point = { -0.25, 0, 4.75 } },
                 max_tension = block_weight / 4 }
    s:add_cable{ from = { block = cube, point = { 0.25, 0, 2.5 } }, to = { block = beam, point = { 0.25, 0, 4.75 } } }
    local r = ashlar.analyze(s)
    assert.is_false(r.stable)  -- unequal tensions leave a torque
    near(r.cables[1].tension, block_weight / 4, 1e-5 * block_weight)
    near(r.cables[2].tension, 3 * block_weight / 4, 1e-5 * block_weight)
    near(r.blocks[2].virtual_torque[2], 0.25 * block_weight / 2, 1e-5 * block_weight)
    assert.are.equal(block_weight / 4, s:cables()[1].max_tension)
  end)

  it("are saved, loaded and exported", function()
    local s = hanging_cube(0.25, { mass_per_length = 3, max_tension = 1e6 })
    local folder = support.temp_folder()
    s:save(folder .. "/cable.json")
    local loaded = ashlar.load(folder .. "/cable.json")
    local c = loaded:cables()[1]
    assert.are.same({ 0.25, 0, 2.5 }, c.from.point)
    assert.are.equal(2, c.from.block)
    assert.are.equal(3, c.mass_per_length)
    assert.are.equal(1e6, c.max_tension)
    near(c.length, 2.25, 1e-12)
    near(ashlar.analyze(loaded).penalty, ashlar.analyze(s).penalty, 1e-12)
    ashlar.export_qp(s, folder .. "/cable.qps")
    local text = assert(io.open(folder .. "/cable.qps")):read("a")
    assert.truthy(text:find(" UP BND T1 ", 1, true))
    assert.truthy(text:find("    P2 B2M2 1", 1, true))
    ashlar.export(s, folder .. "/cable.gltf", { cable_color = { 1, 0, 0 } })
    local gltf = assert(io.open(folder .. "/cable.gltf")):read("a")
    assert.truthy(gltf:find('"name":%s*"cable 1"'))
    expect_error({ "cable_color: colour components must lie in [0, 1]" },
      function() ashlar.export(s, folder .. "/bad.glb", { cable_color = { 2, 0, 0 } }) end)
    os.execute("rm -r " .. support.quote(folder))
  end)

  it("reject bad input with clear messages", function()
    local s = hanging_cube(0)
    expect_error({ "from: required" }, function() s:add_cable{ to = { block = 1, point = { 0, 0, 5 } } } end)
    expect_error({ "from.block: index 9 is out of range" },
      function() s:add_cable{ from = { block = 9, point = { 0, 0, 0 } }, to = { block = 1, point = { 0, 0, 5 } } } end)
    expect_error({ "cable 2 'from': point is not on block 2" },
      function() s:add_cable{ from = { block = 2, point = { 0, 0, 9 } }, to = { block = 1, point = { 0, 0, 5 } } } end)
    expect_error({ "cable 2: its two ends are at the same point" },
      function() s:add_cable{ from = { block = 2, point = { 0, 0, 2.5 } }, to = { block = 2, point = { 0, 0, 2.5 } } } end)
    expect_error({ "max_tension: expected a number > 0" },
      function() s:add_cable{ from = { block = 2, point = { 0, 0, 2.5 } }, to = { block = 1, point = { 0, 0, 5 } }, max_tension = -1 } end)
    expect_error({ "unknown option 'from.blok'" },
      function() s:add_cable{ from = { blok = 2, point = { 0, 0, 2.5 } }, to = { block = 1, point = { 0, 0, 5 } } } end)
    local dangling = hanging_cube(0)
    dangling:add_cable{ from = { block = 2, point = { 0.5, 0, 2.5 } }, to = { point = { 1, 0, 3.5 } } }
    expect_error({ "cable 2 'to': the end is on no block and meets no other cable end" }, ashlar.analyze, dangling)
    local planar = hanging_cube(0)
    planar:set_planar(true)
    planar:add_cable{ from = { block = 2, point = { 0.5, 0.5, 2.5 } }, to = { block = 1, point = { 0.5, 0.5, 4.75 } } }
    expect_error({ "planar structure: cable 2 leaves the x-z plane" }, ashlar.analyze, planar)
  end)
end)
