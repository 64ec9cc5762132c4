-- s:remove(i): block count and weight, the renumbering of loads and cables,
-- names, the error for a bad index, and an arch without its keystone.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

local function total_mass(s) return support.free_total(s, "mass") end

describe("s:remove", function()
  it("removes one block: count, weight and the renumbering of loads, cables and names", function()
    local s = models.arch{ voussoirs = 9 }  -- voussoirs 1..9, supports 10 and 11
    local mass, old5 = total_mass(s), s:block(5):centroid()
    local removed_mass = s:block(2):mass()
    s:add_load{ block = 5, force = { 0, 0, -1000 } }
    s:add_load{ block = 2, force = { 0, 0, -500 } }
    s:add_cable{ from = { block = 1, point = s:block(1):centroid() }, to = { block = 9, point = s:block(9):centroid() } }
    s:add_cable{ from = { block = 2, point = s:block(2):centroid() }, to = { block = 8, point = s:block(8):centroid() } }
    local block = s:remove(2)
    near(block:mass(), removed_mass, 0, "the removed block is returned")
    assert.equal(10, #s)
    near(total_mass(s), mass - removed_mass, 1e-12 * mass, "mass")
    -- The load on old block 5 is on new block 4, the same block; block 2's went with it.
    local loads = s:loads()
    assert.equal(1, #loads)
    assert.equal(4, loads[1].block)
    near(loads[1].force[3], -1000, 0)
    local c = s:block(4):centroid()
    for k = 1, 3 do near(c[k], old5[k], 0, "centroid of new block 4") end
    assert.equal("voussoir 5", s:name(4))
    assert.equal(9, s:find("support left"))
    assert.is_nil(s:find("voussoir 2"))
    local cables = s:cables()
    assert.equal(1, #cables)
    assert.equal(1, cables[1].from.block)
    assert.equal(8, cables[1].to.block)
  end)

  it("refuses a bad index, naming the argument and the value", function()
    local s = models.column{ drums = 2 }  -- 2 drums and a support
    expect_error({ "bad argument #1 to 'remove' (block: index 4 is out of range (the structure has 3 blocks))" },
      function() s:remove(4) end)
    expect_error({ "bad argument #1 to 'remove' (block: index 0 is out of range (the structure has 3 blocks))" },
      function() s:remove(0) end)
    expect_error({ "bad argument #1 to 'remove' (block: expected a block index or name, got number)" },
      function() s:remove(1.5) end)
    expect_error({ "bad argument #1 to 'remove' (block: no block is named 'drum 9')" }, function() s:remove("drum 9") end)
    assert.equal(3, #s)
  end)

  it("takes a name, and the contacts follow", function()
    local s = models.column{ drums = 3 }
    assert.equal(3, #s:interfaces())  -- ground-drum 1, drum 1-2, drum 2-3
    s:remove("drum 2")
    assert.equal(3, #s)
    assert.equal(1, #s:interfaces())  -- drum 3 now hangs a drum's height above drum 1
  end)

  it("an arch that stands falls without its keystone", function()
    local s = models.arch{ voussoirs = 9 }
    assert.is_true(ashlar.analyze(s, { friction = 0.7 }).stable)
    assert.equal("voussoir 5", s:name(5))
    s:remove(5)
    local r = ashlar.analyze(s, { friction = 0.7 })
    assert.equal("converged", r.status)
    assert.is_false(r.stable)
    assert.is_true(r.infeasibility > 0.01)
  end)
end)
