-- A floating block says why: the nearest block it misses and the contact
-- tolerance that closes the gap (a column whose blocks were modelled with
-- 0.5 mm gaps, as imported models often are).
local ashlar = require "ashlar"

local function column_with_gaps(gap)
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true })
  local z = 0
  for _ = 1, 4 do
    z = z + gap
    s:add(ashlar.box{ size = { 0.3, 0.3, 0.3 }, center = { 0, 0, z + 0.15 } })
    z = z + 0.3
  end
  return s
end

describe("a floating block", function()
  it("names the block it misses, the gap, and the contact tolerance that closes it", function()
    local s = column_with_gaps(0.0005)
    local r = ashlar.analyze(s)
    assert.is_false(r.stable)
    assert.same({ 2, 3, 4, 5 }, r.floating)
    for i = 2, 5 do
      assert.is_true(r.blocks[i].floating)
      assert.equal(i - 1, r.blocks[i].nearest)  -- the block below (ties: the first found)
      assert.near(0.0005, r.blocks[i].gap, 1e-3 * 0.0005)
    end
    assert.matches("4 blocks float: block 2 is 0.0005%d* m from block 1 %(contact_tolerance = 0.0005%d* closes it%)",
      tostring(r))
    -- Named blocks are named too.
    local named = ashlar.structure()
    named:add(s:block(1), { support = true, name = "plinth" })
    named:add(s:block(2), { name = "drum" })
    assert.matches("1 block floats: block 2 %('drum'%) is 0.0005%d* m from block 1 %('plinth'%)", tostring(ashlar.analyze(named)))
    local closed = ashlar.analyze(s, { contact_tolerance = r.blocks[2].gap })
    assert.is_true(closed.stable)
    assert.same({}, closed.floating)
    assert.is_nil(closed.blocks[2].gap)
  end)

  it("says so when nothing is near", function()
    local s = column_with_gaps(0.5)
    local r = ashlar.analyze(s)
    assert.is_nil(r.blocks[2].nearest)
    assert.matches("block 2 touches nothing within 1 %% of the structure's size", tostring(r))
  end)

  it("is among the near misses s:contact_report lists, with what the tolerance closes", function()
    -- Gaps of 10 and 30 micrometres: the default tolerance (1e-6 of the
    -- model's size, 1.6 micrometres here) misses both; range 10 reaches the
    -- first only, range 100 both, in order of their gaps.
    local s = ashlar.structure()
    s:add(ashlar.box{ size = { 1, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true })
    s:add(ashlar.box{ size = { 0.3, 0.3, 0.3 }, center = { 0, 0, 0.15 + 3e-5 } })
    s:add(ashlar.box{ size = { 0.3, 0.3, 0.3 }, center = { 0, 0, 0.45 + 4e-5 } })
    local near = s:contact_report()
    assert.near(1e-6 * math.sqrt(1 + 1 + 0.8 ^ 2), near.tolerance, 1e-9)
    assert.equal(1, #near.gaps)
    assert.same({ 2, 3 }, { near.gaps[1].a, near.gaps[1].b })
    assert.near(1e-5, near.gaps[1].gap, 1e-3 * 1e-5 + 1e-10)
    assert.same({}, near.overlaps)
    local far = s:contact_report{ range = 100 }
    assert.equal(2, #far.gaps)
    assert.same({ 1, 2 }, { far.gaps[2].a, far.gaps[2].b })
    assert.near(3e-5, far.gaps[2].gap, 1e-3 * 3e-5 + 1e-10)
    -- An explicit tolerance that closes the first gap leaves the second.
    local closed = s:contact_report{ tolerance = 2e-5, range = 2 }
    assert.equal(1, #closed.gaps)
    assert.same({ 1, 2 }, { closed.gaps[1].a, closed.gaps[1].b })
    require("spec_support").expect_error({ "range", "got 1" }, s.contact_report, s, { range = 1 })
  end)
end)
