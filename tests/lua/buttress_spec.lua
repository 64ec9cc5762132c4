-- models.flying_buttress: blocks, contacts implied by the topology, exact
-- volume, option errors, and the thesis's claim (figures 6 and 7) that the
-- pier needs weight on its top to take the flyer's thrust.
local ashlar = require "ashlar"
local flying_buttress = require "ashlar.models.flying_buttress"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

-- Flyer: N trapezoids of the quarter annulus (straight chords for intrados
-- and extrados); pier and pinnacle: boxes.
local function expected_volume(o)
  local inner, outer = o.radius - o.thickness / 2, o.radius + o.thickness / 2
  local flyer = o.voussoirs * 0.5 * (outer ^ 2 - inner ^ 2) * math.sin(0.5 * math.pi / o.voussoirs)
  return (flyer + o.pier_width * o.pier_height + (o.pier_width - o.thickness) * o.pinnacle_height) * o.depth
end

describe("models.flying_buttress", function()
  local cases = {
    { radius = 6, thickness = 0.8, voussoirs = 60, depth = 1, pier_width = 1.4, pier_height = 12,
      pier_blocks = 4, pinnacle_height = 4 },                                 -- the defaults
    { radius = 3, thickness = 0.5, voussoirs = 5, depth = 0.7, pier_width = 1.3, pier_height = 7,
      pier_blocks = 6, pinnacle_height = 0 },
  }
  for k, o in ipairs(cases) do
    local s = k == 1 and flying_buttress() or flying_buttress(o)
    local pinnacle = o.pinnacle_height > 0 and 1 or 0

    it(("case %d: blocks, names and supports"):format(k), function()
      assert.equal(o.voussoirs + o.pier_blocks + pinnacle + 2, #s)
      for i = 1, o.voussoirs do assert.equal(("voussoir %d"):format(i), s:name(i)) end
      for i = 1, o.pier_blocks do assert.equal(("pier %d"):format(i), s:name(o.voussoirs + i)) end
      assert.equal(pinnacle == 1, s:find("pinnacle") ~= nil)
      assert.equal(#s - 1, s:find("wall")); assert.equal(#s, s:find("ground"))
      for i = 1, #s do assert.equal(i >= #s - 1, s:is_support(i)) end
      -- Voussoirs from the wall down to the pier.
      for i = 2, o.voussoirs do
        assert.is_true(s:block(i):centroid()[1] > s:block(i - 1):centroid()[1])
        assert.is_true(s:block(i):centroid()[3] < s:block(i - 1):centroid()[3])
      end
    end)

    it(("case %d: exactly the contacts of the topology"):format(k), function()
      local contacts = {}
      local function add(a, b, area) contacts[#contacts + 1] = { a, b, area } end
      local joint = o.thickness * o.depth
      add("wall", "voussoir 1", joint)
      for i = 1, o.voussoirs - 1 do add(("voussoir %d"):format(i), ("voussoir %d"):format(i + 1), joint) end
      add(("voussoir %d"):format(o.voussoirs), ("pier %d"):format(o.pier_blocks), joint)
      local bed = o.pier_width * o.depth
      for i = 1, o.pier_blocks - 1 do add(("pier %d"):format(i), ("pier %d"):format(i + 1), bed) end
      add("pier 1", "ground", bed)
      if pinnacle == 1 then
        add(("pier %d"):format(o.pier_blocks), "pinnacle", (o.pier_width - o.thickness) * o.depth)
      end
      support.expect_contacts(s, contacts)
    end)

    it(("case %d: volume of the polyhedral shape; crown and springing joints"):format(k), function()
      local volume = expected_volume(o)
      near(support.free_volume(s), volume, 1e-12 * volume)
      local lo, hi = s:bounds()
      near(lo[2], -o.depth / 2, 1e-15); near(hi[2], o.depth / 2, 1e-15)
      for _, f in ipairs(s:interfaces()) do
        local names = s:name(f.a) .. "/" .. s:name(f.b)
        if names:find("wall") then
          near(math.abs(f.normal[1]), 1, 1e-15, "crown joint normal")
          near(f.center[3], o.pier_height + o.radius, 1e-12, "crown joint height")
        elseif names:find(("voussoir %d"):format(o.voussoirs), 1, true) and names:find("pier") then
          near(math.abs(f.normal[3]), 1, 1e-15, "springing normal")
          near(f.center[1], o.radius, 1e-12, "springing centre")
          near(f.center[3], o.pier_height, 1e-12, "springing height")
        end
      end
    end)
  end

  it("stands with its pinnacle and falls without it or with a light one", function()
    -- Flyer R = 6, t = 0.8 on a pier 12 m x 1.4 m: the pinnacle's weight
    -- on the pier's top moves the resultant of the flyer's thrust and the
    -- pier's weight back into the pier (figure 7, right); the smallest
    -- pinnacle is 2.35 m high. The wall joint works by friction, where the
    -- solve may stop "inaccurate" short of 1e-10; stability is then still
    -- proved by the tension-free forces it found.
    local function analyze(o)
      return ashlar.analyze(flying_buttress(o), { friction = 0.7 })
    end
    for _, o in ipairs{ {}, { pinnacle_height = 2.4 }, { pinnacle_height = 8 }, { pier_blocks = 16 },
                        { pier_blocks = 1 } } do
      local r = analyze(o)
      assert.is_true(r.stable)
      assert.equal(0, r.infeasibility)
    end
    for _, o in ipairs{ { pinnacle_height = 0 }, { pinnacle_height = 2 }, { pinnacle_height = 0, pier_blocks = 16 } } do
      local r = analyze(o)
      assert.is_false(r.stable, "pinnacle height " .. o.pinnacle_height)
      assert.is_true(r.infeasibility > 1e-4, "pinnacle height " .. o.pinnacle_height)
    end
    -- A stockier pier needs no pinnacle.
    local stocky = analyze{ pier_width = 1.6, pinnacle_height = 0 }
    assert.is_true(stocky.stable)
  end)

  it("rejects bad options, naming models.flying_buttress", function()
    expect_error({ "models.flying_buttress: unknown option 'pinacle_height'", "allowed:" }, flying_buttress,
      { pinacle_height = 1 })
    expect_error({ "models.flying_buttress: thickness must be < 2 * radius (12), got 12" }, flying_buttress,
      { thickness = 12, pier_width = 13 })
    expect_error({ "models.flying_buttress: pier_width must be > thickness (0.8)", "got 0.8" }, flying_buttress,
      { pier_width = 0.8 })
    expect_error({ "models.flying_buttress: voussoirs: must be >= 1, got 0" }, flying_buttress, { voussoirs = 0 })
    expect_error({ "models.flying_buttress: pier_blocks: expected an integer, got 2.5" }, flying_buttress,
      { pier_blocks = 2.5 })
    expect_error({ "models.flying_buttress: pinnacle_height: must be >= 0, got -1" }, flying_buttress,
      { pinnacle_height = -1 })
    expect_error({ "models.flying_buttress: pier_height: must be > 0" }, flying_buttress, { pier_height = 0 })
    expect_error({ "models.flying_buttress: radius: expected a finite number" }, flying_buttress,
      { radius = 0 / 0 })
    expect_error({ "models.flying_buttress: expected an option table, got string" }, flying_buttress, "big")
  end)
end)
