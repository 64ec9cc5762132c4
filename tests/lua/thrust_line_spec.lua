-- The thrust line follows the force path's branches wherever it is drawn or
-- returned: r:thrust_lines() gives every branch (as ashlar.draw draws them),
-- r:thrust_line() the longest, and for a chain of blocks both are the line.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local function distance(p, q)
  return math.sqrt((p[1] - q[1]) ^ 2 + (p[2] - q[2]) ^ 2 + (p[3] - q[3]) ^ 2)
end

-- The largest bounding-box diagonal of the structure's blocks: no step of a
-- thrust line crosses more than one block.
local function largest_block(s)
  local largest = 0
  for i = 1, #s do
    local lo, hi = s:block(i):bounds()
    largest = math.max(largest, distance(lo, hi))
  end
  return largest
end

describe("the thrust line", function()
  it("branches at the pier of a two-span arcade instead of jumping across", function()
    local s = models.arch_bridge{ spans = 2, spandrel = false }
    local r = ashlar.analyze(s, { friction = 0.7 })
    assert.is_true(r.stable)
    local reach = largest_block(s)
    local branches = r:thrust_lines()
    assert.is_true(#branches >= 3)  -- two arches and the pier meet
    local seen = {}
    for _, branch in ipairs(branches) do
      for k = 2, #branch do
        assert.is_true(distance(branch[k - 1], branch[k]) <= reach,
          ("a step of %.2f m, blocks are at most %.2f m"):format(distance(branch[k - 1], branch[k]), reach))
      end
      for _, p in ipairs(branch) do seen[#seen + 1] = p end
    end
    -- Every compressed interface's centre of pressure is on some branch.
    local largest = 0
    for _, f in ipairs(r.interfaces) do largest = math.max(largest, f.normal_force) end
    for _, f in ipairs(r.interfaces) do
      if f.normal_force > 1e-3 * largest then
        local found = false
        for _, p in ipairs(seen) do found = found or distance(p, f.center_of_pressure) == 0 end
        assert.is_true(found, ("interface %d-%d is on no branch"):format(f.a, f.b))
      end
    end
    -- The longest branch, without the jump across the pier it made before.
    local line = r:thrust_line()
    assert.is_true(#line >= 26)
    for k = 2, #line do assert.is_true(distance(line[k - 1], line[k]) <= reach) end
  end)

  it("is one line along a chain of blocks, from a support", function()
    local s = models.arch{ voussoirs = 16 }
    local r = ashlar.analyze(s, { friction = 0.7 })
    local branches, line = r:thrust_lines(), r:thrust_line()
    assert.equal(1, #branches)
    assert.equal(17, #line)  -- every joint of 16 voussoirs between two supports
    assert.same(line, branches[1][1][1] == line[1][1] and branches[1] or (function()
      local reversed = {}
      for k = #branches[1], 1, -1 do reversed[#reversed + 1] = branches[1][k] end
      return reversed
    end)())
    -- from the springing on a support
    assert.is_true(line[1][3] < 0.5)
  end)
end)
