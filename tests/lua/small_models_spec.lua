-- The small generators (models.column, models.stack, models.post_and_lintel,
-- models.h_frame): topology, exact volumes, symmetry, option errors, and
-- equilibrium, including the overhang limit of a stack against its closed
-- form.
local ashlar = require "ashlar"
local column = require "ashlar.models.column"
local stack = require "ashlar.models.stack"
local post_and_lintel = require "ashlar.models.post_and_lintel"
local h_frame = require "ashlar.models.h_frame"

local support = require "spec_support"
local total_volume = support.free_volume
local near, expect_error = support.near, support.expect_error

-- Every block here is a box, so two overlap exactly when their bounding
-- boxes share a volume.
local function expect_no_overlaps(s)
  for i = 1, #s do
    local lo_i, hi_i = s:block(i):bounds()
    for j = i + 1, #s do
      local lo_j, hi_j = s:block(j):bounds()
      local apart = false
      for k = 1, 3 do
        apart = apart or math.min(hi_i[k], hi_j[k]) - math.max(lo_i[k], lo_j[k]) <= 1e-12
      end
      assert(apart, ("%s overlaps %s"):format(s:name(i), s:name(j)))
    end
  end
end

-- The interfaces as a set of "name a | name b" keys, with their areas;
-- fails on a pair seen twice.
local function contacts(s)
  local set, count = {}, 0
  for _, f in ipairs(s:interfaces()) do
    local key = s:name(f.a) .. " | " .. s:name(f.b)
    assert(set[key] == nil, "two interfaces for " .. key)
    set[key], count = f, count + 1
  end
  return set, count
end

-- Asserts that the interfaces are exactly `expected` ({ {name a, name b,
-- area}, ... }, a before b in block order): none missing, none spurious,
-- each a whole face of the given area.
local function expect_contacts(s, expected)
  local set, count = contacts(s)
  for _, e in ipairs(expected) do
    local key = e[1] .. " | " .. e[2]
    local f = set[key]
    assert(f, "missing interface " .. key)
    near(f.area, e[3], 1e-12 * math.max(1, e[3]), key .. " area")
  end
  assert.equal(#expected, count)
  expect_no_overlaps(s)
end

-- Stable is proved by the solver's forces themselves, whatever its status;
-- near a limit a solve may stop short, which counts as not proven stable.
local function stands(s, friction)
  return ashlar.analyze(s, { friction = friction or 0.7 }).stable
end

describe("models.column", function()
  local s = column{ height = 3, width = 0.5, depth = 0.4, drums = 6, density = 2000 }

  it("has its drums from the bottom, then the ground", function()
    assert.equal(7, #s)
    for i = 1, 6 do
      assert.equal(("drum %d"):format(i), s:name(i))
      assert.is_false(s:is_support(i))
      near(s:block(i):centroid()[3], (i - 0.5) * 0.5, 1e-15)
    end
    assert.equal(7, s:find("ground"))
    assert.is_true(s:is_support("ground"))
    assert.equal(6, #column{ ground = false })
    for i = 1, 6 do assert.is_false(column{ ground = false }:is_support(i)) end
  end)

  it("has one whole-face joint per drum, the ground's included", function()
    local expected = { { "drum 1", "ground", 0.2 } }
    for i = 1, 5 do expected[#expected + 1] = { ("drum %d"):format(i), ("drum %d"):format(i + 1), 0.2 } end
    expect_contacts(s, expected)
  end)

  it("has the volume of its prism and stands on the z axis", function()
    near(total_volume(s), 3 * 0.5 * 0.4, 1e-12)
    near(s:block(1):mass(), 2000 * 0.5 * 0.5 * 0.4, 1e-9)
    for i = 1, 6 do
      local c = s:block(i):centroid()
      near(c[1], 0, 1e-15); near(c[2], 0, 1e-15)
    end
  end)

  it("stands", function()
    assert.is_true(stands(s))
    assert.is_true(stands(column{}))
  end)

  it("rejects bad options, naming models.column", function()
    expect_error({ "models.column: unknown option 'drum'", "allowed:" }, column, { drum = 3 })
    expect_error({ "models.column: drums: must be >= 1, got 0" }, column, { drums = 0 })
    expect_error({ "models.column: drums: expected an integer, got 2.5" }, column, { drums = 2.5 })
    expect_error({ "models.column: height: must be > 0, got -1" }, column, { height = -1 })
    expect_error({ "models.column: width: expected a finite number" }, column, { width = 0 / 0 })
    expect_error({ "models.column: ground: expected a boolean, got string" }, column, { ground = "yes" })
  end)
end)

describe("models.stack", function()
  it("has its blocks from the bottom, each shifted by the offset, then the ground", function()
    local s = stack{ blocks = 5, size = { 1, 0.8, 0.5 }, offset = 0.1 }
    assert.equal(6, #s)
    for i = 1, 5 do
      assert.equal(("block %d"):format(i), s:name(i))
      local c = s:block(i):centroid()
      near(c[1], (i - 1) * 0.1, 1e-12); near(c[2], 0, 1e-15); near(c[3], (i - 0.5) * 0.5, 1e-15)
    end
    assert.is_true(s:is_support("ground"))
    assert.equal(6, s:find("ground"))
    assert.equal(5, #stack{ ground = false })
  end)

  it("has one joint per block, the area of the blocks' overlap", function()
    local offsets = { 0.3, -0.1, 0.25 }
    local s = stack{ blocks = 4, size = { 1, 0.8, 0.5 }, offsets = offsets }
    local expected = { { "block 1", "ground", 0.8 } }
    for i = 1, 3 do
      expected[#expected + 1] = { ("block %d"):format(i), ("block %d"):format(i + 1), (1 - math.abs(offsets[i])) * 0.8 }
    end
    expect_contacts(s, expected)
    near(s:block(4):centroid()[1], 0.45, 1e-12)
    near(total_volume(s), 4 * 1 * 0.8 * 0.5, 1e-12)
  end)

  it("stands with 5 blocks of width 1 at offset 0.1", function()
    assert.is_true(stands(stack{ blocks = 5, size = { 1, 1, 0.5 }, offset = 0.1 }))
  end)

  -- Block i (from the bottom) sits at (i - 1) d. The k blocks above the
  -- joint on top of block j have their centroid at d (j + (k + 1) / 2 - 1),
  -- (k + 1) d / 2 beyond block j's centre ((k - 1) d / 2 beyond the lowest
  -- of them); it must lie over the contact, whose far edge is b / 2 beyond
  -- block j's centre: (k + 1) d <= b. The joint on block 1 (k = n - 1) is
  -- the worst, and the ground (which holds all of block 1) asks only
  -- (n - 1) d <= b: the largest uniform offset is b / n, whatever the
  -- friction (no horizontal force acts).
  it("stands up to the closed-form largest uniform offset b / n", function()
    local b = 1.3
    for _, n in ipairs{ 2, 3, 5, 8 } do
      local function holds(d) return stands(stack{ blocks = n, size = { b, 0.6, 0.4 }, offset = d }, 0.7) end
      local closed = b / n
      local low, high = 0.5 * closed, 1.5 * closed
      assert.is_true(holds(low)); assert.is_false(holds(high))
      while high - low > 1e-6 * closed do
        local middle = (low + high) / 2
        if holds(middle) then low = middle else high = middle end
      end
      near((low + high) / 2, closed, 1e-4 * closed, ("%d blocks"):format(n))
    end
  end)

  -- The harmonic stack: block j + 1 shifted b / (2k) beyond block j, with k
  -- blocks above that joint, puts every joint exactly at its limit.
  it("stands just inside the harmonic overhang and falls just outside", function()
    local n, b = 6, 1
    local function harmonic(scale)
      local offsets = {}
      for j = 1, n - 1 do offsets[j] = scale * b / (2 * (n - j)) end
      return stack{ blocks = n, size = { b, 1, 0.3 }, offsets = offsets }
    end
    assert.is_true(stands(harmonic(0.999)))
    assert.is_false(stands(harmonic(1.001)))
  end)

  it("rejects bad options, naming models.stack", function()
    expect_error({ "models.stack: unknown option 'offest'", "allowed:" }, stack, { offest = 0.1 })
    expect_error({ "models.stack: blocks: must be >= 1, got 0" }, stack, { blocks = 0 })
    expect_error({ "models.stack: size[3]: must be > 0, got 0" }, stack, { size = { 1, 1, 0 } })
    expect_error({ "models.stack: size: expected a table of 3 numbers" }, stack, { size = { 1, 1 } })
    expect_error({ "models.stack: offset: must be smaller in magnitude than the block width size[1] = 1, got 1" },
      stack, { offset = 1 })
    expect_error({ "models.stack: offset: must be smaller in magnitude than the block width size[1] = 1, got -1.5" },
      stack, { offset = -1.5 })
    expect_error({ "models.stack: offsets[2]: must be smaller in magnitude than the block width size[1] = 1, got 2" },
      stack, { blocks = 3, offsets = { 0.1, 2 } })
    expect_error({ "models.stack: offsets: expected 4 numbers (one per block above the first), got 2" },
      stack, { offsets = { 0.1, 0.2 } })
    expect_error({ "models.stack: offsets[1]: expected a finite number" }, stack, { blocks = 2, offsets = { "x" } })
    expect_error({ "models.stack: give either offset or offsets, not both" }, stack,
      { blocks = 2, offset = 0.1, offsets = { 0.1 } })
    expect_error({ "models.stack: offsets: expected a table, got number" }, stack, { offsets = 0.1 })
  end)
end)

describe("models.post_and_lintel", function()
  it("has the lintel, the posts from left to right and the ground, joined at whole faces", function()
    local s = post_and_lintel{ span = 3, lintel = { 4.5, 0.5, 0.4 },
                               posts = { { width = 0.4, height = 2 }, { width = 0.8, height = 2 } } }
    assert.equal(4, #s)
    assert.same({ "lintel", "post left", "post right", "ground" }, { s:name(1), s:name(2), s:name(3), s:name(4) })
    assert.is_true(s:is_support("ground"))
    for i = 1, 3 do assert.is_false(s:is_support(i)) end
    expect_contacts(s, {
      { "lintel", "post left", 0.4 * 0.5 }, { "lintel", "post right", 0.8 * 0.5 },
      { "post left", "ground", 0.4 * 0.5 }, { "post right", "ground", 0.8 * 0.5 },
    })
    -- The posts' outer faces are 3 + 0.4 + 0.8 = 4.2 apart, centred.
    near(s:block("post left"):centroid()[1], -2.1 + 0.2, 1e-12)
    near(s:block("post right"):centroid()[1], 2.1 - 0.4, 1e-12)
    near(s:block("lintel"):centroid()[3], 2.2, 1e-12)
    near(total_volume(s), 4.5 * 0.5 * 0.4 + (0.4 + 0.8) * 2 * 0.5, 1e-12)
  end)

  it("takes three posts as in figure 14, the middle one numbered", function()
    local s = post_and_lintel{ span = 1.5, posts = { { width = 0.3 }, { width = 0.9 }, { width = 0.6 } } }
    assert.same({ "lintel", "post left", "post 2", "post right", "ground" },
      { s:name(1), s:name(2), s:name(3), s:name(4), s:name(5) })
    -- The default lintel is exactly as long as the posts and openings.
    local lo, hi = s:block("lintel"):bounds()
    near(hi[1] - lo[1], 3 + 1.8, 1e-12)
    local expected = {}
    for _, p in ipairs{ { "post left", 0.3 }, { "post 2", 0.9 }, { "post right", 0.6 } } do
      expected[#expected + 1] = { "lintel", p[1], p[2] * 0.5 }
    end
    for _, p in ipairs{ { "post left", 0.3 }, { "post 2", 0.9 }, { "post right", 0.6 } } do
      expected[#expected + 1] = { p[1], "ground", p[2] * 0.5 }
    end
    expect_contacts(s, expected)
    near(total_volume(s), 4.8 * 0.5 * 0.5 + 1.8 * 2 * 0.5, 1e-12)
    assert.is_true(stands(s))
  end)

  it("is symmetric with equal posts", function()
    local s = post_and_lintel{ posts = { { width = 0.5 }, { width = 0.5 } } }
    local l, r = s:block("post left"):centroid(), s:block("post right"):centroid()
    near(l[1], -r[1], 1e-15); near(l[3], r[3], 1e-15)
    near(s:block("lintel"):centroid()[1], 0, 1e-15)
  end)

  it("stands", function()
    assert.is_true(stands(post_and_lintel{}))
  end)

  it("rejects bad options, naming models.post_and_lintel", function()
    expect_error({ "models.post_and_lintel: unknown option 'post'", "allowed:" }, post_and_lintel, { post = {} })
    expect_error({ "models.post_and_lintel: posts: expected at least 2 posts, got 1" }, post_and_lintel,
      { posts = { { width = 1 } } })
    expect_error({ "models.post_and_lintel: posts[2]: unknown option 'widht'", "allowed: height, width" },
      post_and_lintel, { posts = { {}, { widht = 1 } } })
    expect_error({ "models.post_and_lintel: posts[1]: width: must be > 0, got 0" }, post_and_lintel,
      { posts = { { width = 0 }, {} } })
    expect_error({ "models.post_and_lintel: posts[2]: height 2.5 differs from posts[1]'s 2" }, post_and_lintel,
      { posts = { {}, { height = 2.5 } } })
    expect_error({ "models.post_and_lintel: lintel[1] (length) must be >= 4.8, the posts and openings together, got 4" },
      post_and_lintel, { lintel = { 4, 0.5, 0.5 } })
    expect_error({ "models.post_and_lintel: span: must be > 0, got 0" }, post_and_lintel, { span = 0 })
    expect_error({ "models.post_and_lintel: posts[1]: expected an option table, got number" }, post_and_lintel,
      { posts = { 1, 2 } })
  end)
end)

describe("models.h_frame", function()
  local H, w, d, gap, courses = 3, 0.4, 0.5, 1.2, 5
  local h = H / courses

  for _, beam in ipairs{ "through", "between" } do
    local s = h_frame{ height = H, width = w, depth = d, gap = gap, courses = courses, beam = beam }
    local skip = beam == "through" and 3 or nil

    it(beam .. ": has the posts' blocks, the beam and the ground", function()
      local posts = beam == "through" and courses - 1 or courses
      assert.equal(2 * posts + 2, #s)
      assert.equal(2 * posts + 1, s:find("beam"))
      assert.equal(2 * posts + 2, s:find("ground"))
      assert.is_true(s:is_support("ground"))
      for i = 1, #s - 1 do assert.is_false(s:is_support(i)) end
      for c = 1, courses do
        assert.equal(c ~= skip, s:find(("post left %d"):format(c)) ~= nil)
        assert.equal(c ~= skip, s:find(("post right %d"):format(c)) ~= nil)
      end
    end)

    it(beam .. ": has the joints of its topology, at whole faces", function()
      local expected = {}
      for _, side in ipairs{ "left", "right" } do
        local function post(c) return ("post %s %d"):format(side, c) end
        expected[#expected + 1] = { post(1), "ground", w * d }
        for c = 1, courses - 1 do
          if c + 1 == skip then
            expected[#expected + 1] = { post(c), "beam", w * d }
          elseif c == skip then
            expected[#expected + 1] = { post(c + 1), "beam", w * d }
          else
            expected[#expected + 1] = { post(c), post(c + 1), w * d }
          end
        end
        if beam == "between" then expected[#expected + 1] = { post(3), "beam", h * d } end
      end
      expect_contacts(s, expected)
    end)

    it(beam .. ": has the volume of the H and is symmetric", function()
      near(total_volume(s), (2 * w * H + gap * h) * d, 1e-12)
      for c = 1, courses do
        if c ~= skip then
          local l, r = s:block(("post left %d"):format(c)):centroid(), s:block(("post right %d"):format(c)):centroid()
          near(l[1], -r[1], 1e-15); near(l[3], r[3], 1e-15); near(l[1], -(gap + w) / 2, 1e-15)
        end
      end
      local c = s:block("beam"):centroid()
      near(c[1], 0, 1e-15); near(c[3], H / 2, 1e-12)
    end)
  end

  it("stands with the beam through the posts", function()
    assert.is_true(stands(h_frame{}))
  end)

  -- Wedged between slender posts, the beam's outward thrust (at least
  -- W / (2 friction) on each post) overturns them; squat, heavy posts take it.
  it("with the beam between the posts, stands only on squat posts", function()
    assert.is_false(stands(h_frame{ beam = "between" }))
    assert.is_true(stands(h_frame{ beam = "between", width = 2, gap = 0.5 }))
  end)

  -- The beam's weight W reaches each post as friction V = W / 2 on its end
  -- face, which needs a thrust N >= V / friction. Each post is a stack whose
  -- joints must hold the loads above them: under the beam, the joint
  -- j = m - 1 slides unless N <= friction ((C - m + 1) G + V), and joint j
  -- (0 = ground) tips outwards unless N (m - 1 - j) h <= (C - j) G w / 2 + V w,
  -- with the thrust at the beam's lowest point (the least moment). The
  -- least friction coefficient at which the frame stands is the largest
  -- root of these (the friction pyramid is exact along the contacts' edges).
  it("with the beam between the posts, stands from the closed-form least friction", function()
    local cases = {
      { beam = "between" },
      { beam = "between", courses = 3 },
      { beam = "between", courses = 7, gap = 0.8, width = 0.5 },
      { beam = "between", courses = 3, gap = 3, height = 1, depth = 0.7 },
    }
    for k, o in ipairs(cases) do
      local C, w, g = o.courses or 5, o.width or 0.4, o.gap or 1.2
      local hb, m = (o.height or 3) / C, (C + 1) // 2
      local G, V = w * hb, g * hb / 2            -- per unit depth and weight density
      local closed = math.sqrt(V / ((C - m + 1) * G + V))
      for j = 0, m - 2 do closed = math.max(closed, V * (m - 1 - j) * hb / ((C - j) * G * w / 2 + V * w)) end
      if k == 1 then near(closed, 1.125, 1e-12, "the defaults") end
      local s = h_frame(o)
      local low, high = 0.5 * closed, 2 * closed
      assert.is_false(stands(s, low)); assert.is_true(stands(s, high))
      while high - low > 1e-7 * closed do
        local middle = (low + high) / 2
        if stands(s, middle) then high = middle else low = middle end
      end
      near((low + high) / 2, closed, 1e-5 * closed, "case " .. k)
    end
  end)

  it("rejects bad options, naming models.h_frame", function()
    expect_error({ "models.h_frame: unknown option 'span'", "allowed:" }, h_frame, { span = 2 })
    expect_error({ "models.h_frame: courses: must be odd (one course at mid-height for the beam), got 4" },
      h_frame, { courses = 4 })
    expect_error({ "models.h_frame: courses: must be >= 3, got 1" }, h_frame, { courses = 1, beam = "between" })
    expect_error({ "models.h_frame: beam: 'over' is not one of through, between" }, h_frame, { beam = "over" })
    expect_error({ "models.h_frame: gap: must be > 0, got -1" }, h_frame, { gap = -1 })
  end)
end)
