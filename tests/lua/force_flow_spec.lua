-- ashlar.trace_loads: load traces of one block's weight (Shin 2014,
-- "Force flow", figure 10), and drawing them in exports.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local near, expect_error = support.near, support.expect_error

-- Shares of the traced weight reaching the ground under the left (x < 0)
-- and the right post.
local function shares_by_side(s, flow)
  local left, right = 0, 0
  for _, arrived in ipairs(flow.shares) do
    local post = s:is_support(arrived.a) and arrived.b or arrived.a
    if s:block(post):centroid()[1] < 0 then left = left + arrived.share else right = right + arrived.share end
  end
  return left, right
end

describe("trace_loads", function()
  local s = models.h_frame{}

  it("splits the H frame's beam weight between its posts", function()
    local flow = ashlar.trace_loads(s, "beam", { traces = 400 })
    assert.is_true(flow.valid)
    assert.is_true(flow.stable)
    assert.equal(400, #flow.polylines)
    assert.equal(400, #flow.support)
    local left, right = shares_by_side(s, flow)
    near(left, 0.5, 0.1, "left share")
    near(right, 0.5, 0.1, "right share")
    near(left + right + flow.lost / 400, 1, 1e-12, "every trace counted")
    -- Traces start at the centroid; those that arrive end on the ground.
    local centroid = s:block("beam"):centroid()
    local ground = s:find("ground")
    local interfaces = s:interfaces()
    for k, polyline in ipairs(flow.polylines) do
      assert.same(centroid, polyline[1])
      if flow.support[k] then
        local contact = interfaces[flow.support[k]]
        assert.is_true(contact.a == ground or contact.b == ground)
        near(polyline[#polyline][3], 0, 1e-9, "trace " .. k .. " ends on the ground's top")
      end
    end
    -- Shares list each support interface once, sorted.
    for k = 2, #flow.shares do assert.is_true(flow.shares[k - 1].interface < flow.shares[k].interface) end
  end)

  it("takes a block index as well as a name", function()
    local by_name = ashlar.trace_loads(s, "beam", { traces = 20 })
    local by_index = ashlar.trace_loads(s, s:find("beam"), { traces = 20 })
    assert.same(by_name.polylines, by_index.polylines)
  end)

  it("is deterministic for a seed and changes with it", function()
    local a = ashlar.trace_loads(s, "beam", { traces = 50, seed = 7 })
    local b = ashlar.trace_loads(s, "beam", { traces = 50, seed = 7 })
    local c = ashlar.trace_loads(s, "beam", { traces = 50, seed = 8 })
    assert.same(a.polylines, b.polylines)
    assert.same(a.support, b.support)
    assert.are_not.same(a.polylines, c.polylines)
  end)

  it("starts from random points inside the block", function()
    local flow = ashlar.trace_loads(s, "beam", { traces = 400, start = "random" })
    local beam = s:block("beam")
    local lo, hi = { math.huge, math.huge, math.huge }, { -math.huge, -math.huge, -math.huge }
    for _, p in ipairs(beam:vertices()) do
      for i = 1, 3 do lo[i], hi[i] = math.min(lo[i], p[i]), math.max(hi[i], p[i]) end
    end
    local distinct = {}
    for _, polyline in ipairs(flow.polylines) do
      local start = polyline[1]
      for i = 1, 3 do assert.is_true(start[i] >= lo[i] and start[i] <= hi[i]) end
      distinct[("%.9f %.9f %.9f"):format(start[1], start[2], start[3])] = true
    end
    local count = 0
    for _ in pairs(distinct) do count = count + 1 end
    assert.equal(400, count)
    local left, right = shares_by_side(s, flow)
    near(left, 0.5, 0.1, "left share")
    near(right, 0.5, 0.1, "right share")
  end)

  it("without turning back goes straight down the posts", function()
    local flow = ashlar.trace_loads(s, "beam", { traces = 100, turn_back = false })
    assert.equal(0, flow.lost)
    -- centroid, a post's top under the beam, the joint below it, the ground
    for _, polyline in ipairs(flow.polylines) do assert.equal(4, #polyline) end
  end)

  it("reports a trace that cannot arrive within max_steps as lost", function()
    local flow = ashlar.trace_loads(s, "beam", { traces = 10, max_steps = 1 })
    assert.equal(10, flow.lost)
    for k = 1, 10 do
      assert.is_false(flow.support[k])
      assert.equal(2, #flow.polylines[k])
    end
    assert.same({}, flow.shares)
  end)

  it("accepts the analysis options", function()
    local flow = ashlar.trace_loads(s, "beam", { traces = 10, friction = 0.9, friction_sides = 6 })
    assert.is_true(flow.valid)
  end)

  it("names bad arguments", function()
    expect_error({ "unknown option 'trace'", "traces" }, ashlar.trace_loads, s, "beam", { trace = 10 })
    expect_error({ "traces: expected an integer from 1" }, ashlar.trace_loads, s, "beam", { traces = 0 })
    expect_error({ "traces: expected an integer", "1.5" }, ashlar.trace_loads, s, "beam", { traces = 1.5 })
    expect_error({ "seed: expected an integer from 0" }, ashlar.trace_loads, s, "beam", { seed = -1 })
    expect_error({ "max_steps: expected an integer from 1" }, ashlar.trace_loads, s, "beam", { max_steps = 0 })
    expect_error({ "start: 'middle' is not one of centroid, random" }, ashlar.trace_loads, s, "beam",
      { start = "middle" })
    expect_error({ "turn_back: expected a boolean" }, ashlar.trace_loads, s, "beam", { turn_back = 1 })
    expect_error({ "friction: expected a number >= 0" }, ashlar.trace_loads, s, "beam", { friction = -1 })
    expect_error({ "is a support" }, ashlar.trace_loads, s, "ground")
    expect_error({ "no block is named 'lintel'" }, ashlar.trace_loads, s, "lintel")
    expect_error({ "index 99 is out of range" }, ashlar.trace_loads, s, 99)
    expect_error({ "Structure expected" }, ashlar.trace_loads, {}, 1)
  end)
end)

describe("export with traces", function()
  local s = models.h_frame{}
  local folder

  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  it("draws the traces as one node", function()
    local flow = ashlar.trace_loads(s, "beam", { traces = 40 })
    local path = folder .. "/traces.glb"
    ashlar.export(s, path, { traces = flow, trace_color = { 0.2, 0.8, 0.3 } })
    local text = support.read_file(path)
    assert.truthy(text:find("load traces", 1, true))
    local plain = folder .. "/plain.glb"
    ashlar.export(s, plain)
    assert.falsy(support.read_file(plain):find("load traces", 1, true))
    assert.is_true(#text > #support.read_file(plain))
  end)

  it("names bad trace options", function()
    local path = folder .. "/bad.glb"
    expect_error({ "traces: expected the table ashlar.trace_loads returned" }, ashlar.export, s, path,
      { traces = {} })
    expect_error({ "traces.polylines[1]" }, ashlar.export, s, path,
      { traces = { polylines = { { { 0, 0 } } } } })
    expect_error({ "trace_color: colour components must lie in [0, 1]" }, ashlar.export, s, path,
      { traces = ashlar.trace_loads(s, "beam", { traces = 2 }), trace_color = { 2, 0, 0 } })
  end)
end)
