-- Load capacity and important weights solve one block per orbit of the
-- problem's symmetries (`symmetry`, default true) and hand its answer to
-- the orbit. Checked on a 12 x 6 dome (72 free blocks and the keystone):
-- - against the same analyses solving every block (`symmetry = false`):
--   load capacities to 1e-9 relative (8e-14 measured), important weights
--   to 1e-4 of the largest (1.5e-5 measured: each block's least squares
--   is known to the solver's tolerance, and the warm starts differ);
-- - against physics, with no symmetry code involved: solving every block,
--   the blocks of one course, identical by the dome's symmetry, get the
--   same bounds (to 1e-9) and the same weights (to 1e-4 of the largest).
--   Before the interfaces' friction frames were chosen by height among
--   equally long edges, the 16 x 18 dome's courses spread by up to 1.5 %.
-- An imperfect copy (every vertex moved by up to 1e-6 of its block's size)
-- has no symmetry and solves every block.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local near = support.near

local MERIDIANS, PARALLELS = 12, 6

local function course(s, c)
  local blocks = {}
  for b = 1, MERIDIANS do blocks[b] = s:find(("course %d block %d"):format(c, b)) end
  return blocks
end

describe("a 12 x 6 dome's symmetries (24: 12 turns, 12 mirrors)", function()
  local s = models.dome{ meridians = MERIDIANS, parallels = PARALLELS }

  it("load_capacity: one block per course and the keystone solved, the same bounds as every block solved", function()
    local fast = ashlar.load_capacity(s, { progress = false })
    local every = ashlar.load_capacity(s, { progress = false, symmetry = false })
    assert.are.equal(24, fast.symmetries)
    assert.are.equal(1, every.symmetries)
    assert.is_true(fast.programs < every.programs / 6)
    for i = 1, #s do
      if s:is_support(i) then
        assert.are.equal(false, fast[i])
      else
        assert.are.equal(every[i].min, fast[i].min)
        if every[i].max == math.huge then
          assert.are.equal(math.huge, fast[i].max)
        else
          near(fast[i].max, every[i].max, 1e-9 * every[i].max, s:name(i))
        end
      end
    end
    -- The physics: a course's blocks are alike.
    for c = 1, PARALLELS do
      local blocks = course(s, c)
      local first = every[blocks[1]].max
      for _, i in ipairs(blocks) do
        if first == math.huge then
          assert.are.equal(math.huge, every[i].max)
        else
          near(every[i].max, first, 1e-9 * first, s:name(i))
        end
      end
    end
  end)

  it("important_weights: 7 problems instead of 73, the same sums", function()
    local fast = ashlar.important_weights(s, { progress = false })
    local every = ashlar.important_weights(s, { progress = false, symmetry = false })
    assert.are.equal(24, fast.symmetries)
    assert.are.equal(7, fast.solves)
    assert.are.equal(73, every.solves)
    assert.is_true(fast.iterations >= fast.solves and every.iterations > fast.iterations)
    local largest = 0
    for i = 1, #s do largest = math.max(largest, every[i]) end
    assert.is_true(largest > 0)
    for i = 1, #s do near(fast[i], every[i], 1e-4 * largest, s:name(i)) end
    for c = 1, PARALLELS do
      local blocks = course(s, c)
      for _, i in ipairs(blocks) do near(every[i], every[blocks[1]], 1e-4 * largest, s:name(i)) end
    end
  end)

  it("an imperfect copy has none", function()
    local small = models.dome{ meridians = 8, parallels = 4 }
    local p = models.perturbed(small, { amount = 1e-6, seed = 3 })
    local options = { progress = false, contact_tolerance = 1e-5 }
    local cap = ashlar.load_capacity(p, options)
    assert.are.equal(1, cap.symmetries)
    assert.are.equal("optimal", cap.status)
    assert.are.equal(1, ashlar.important_weights(p, options).symmetries)
  end)

  it("the option is a boolean", function()
    support.expect_error({ "symmetry: expected a boolean, got string" }, ashlar.load_capacity, s, { symmetry = "yes" })
    support.expect_error({ "symmetry: expected a boolean, got number" }, ashlar.important_weights, s, { symmetry = 1 })
  end)
end)
