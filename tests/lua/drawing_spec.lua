-- ashlar.draw (elevations with the line of thrust) and ashlar.legend.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local expect_error = support.expect_error

-- Width and height of a PNG from its IHDR chunk.
local function png_size(data)
  return string.unpack(">I4I4", data, 17)
end

local PNG_SIGNATURE = "\137PNG\r\n\26\n"

-- The point lists of the SVG's stroked, unfilled paths of colour rgb.
local function stroked_paths(svg, rgb)
  local found = {}
  for attributes in svg:gmatch("<path([^>]*)/>") do
    local compact = attributes:gsub(" ", "")
    if compact:find("stroke:rgb(" .. rgb .. ")", 1, true) and compact:find("fill:none", 1, true) then
      local points = {}
      for x, y in attributes:match('d="([^"]*)"'):gmatch("[ML] ([-%d.]+) ([-%d.]+)") do
        points[#points + 1] = { tonumber(x), tonumber(y) }
      end
      found[#found + 1] = points
    end
  end
  return found
end

describe("ashlar.draw", function()
  local dir
  before_each(function() dir = support.temp_folder() end)
  after_each(function() support.remove_folder(dir) end)

  it("draws an arch with its line of thrust to SVG and PNG", function()
    local s = models.arch{}
    local r = ashlar.analyze(s)
    assert.is_true(r.stable)
    ashlar.draw(s, dir .. "/arch.svg", { result = r, thrust = true, thrust_color = { 1, 0, 0 },
                                         title = "arch" })
    ashlar.draw(s, dir .. "/arch.png", { result = r, forces = true, width = 900, height = 500 })

    local png = support.read_file(dir .. "/arch.png")
    assert.equal(PNG_SIGNATURE, png:sub(1, 8))
    local width, height = png_size(png)
    assert.equal(900, width)
    assert.equal(500, height)

    -- One polyline through every centre of pressure of the thrust line,
    -- inside the image.
    local svg = support.read_file(dir .. "/arch.svg")
    assert.is_truthy(svg:find('width="1200pt" height="800pt"', 1, true))
    local lines = stroked_paths(svg, "100%,0%,0%")
    assert.equal(1, #lines)
    assert.equal(#r:thrust_line(), #lines[1])
    for _, p in ipairs(lines[1]) do
      assert.is_true(p[1] > 0 and p[1] < 1200 and p[2] > 0 and p[2] < 800)
    end
    -- The thrust is drawn by default when a result is given.
    ashlar.draw(s, dir .. "/default.svg", { result = r, thrust_color = { 1, 0, 0 } })
    assert.equal(1, #stroked_paths(support.read_file(dir .. "/default.svg"), "100%,0%,0%"))
    ashlar.draw(s, dir .. "/none.svg", { result = r, thrust = false, thrust_color = { 1, 0, 0 } })
    assert.equal(0, #stroked_paths(support.read_file(dir .. "/none.svg"), "100%,0%,0%"))
  end)

  it("takes views and block colours", function()
    local s = models.arch{ voussoirs = 5 }
    local values = {}
    for i = 1, #s do values[i] = i end
    ashlar.draw(s, dir .. "/side.svg", { view = "side", color = { values = values, map = "magma" } })
    ashlar.draw(s, dir .. "/oblique.png", { view = { 1, 1, 0 }, color = { 0.9, 0.8, 0.6 } })
    ashlar.draw(s, dir .. "/front.svg", { view = "front", title = "five voussoirs" })
    for _, name in ipairs{ "side.svg", "oblique.png", "front.svg" } do
      assert.is_truthy(io.open(dir .. "/" .. name), name)
    end
  end)

  it("reports bad options clearly and writes nothing", function()
    local s = models.arch{ voussoirs = 5 }
    local r = ashlar.analyze(s)
    local path = dir .. "/a.svg"
    expect_error({ "bad argument #3", "unknown option 'thrsut'",
                   "allowed: color, force_scale, forces, height, limit, mechanism, mechanism_color, result, thrust" },
      ashlar.draw, s, path, { result = r, thrsut = true })
    expect_error({ "view: expected 'front', 'side' or a horizontal direction", "'top'" },
      ashlar.draw, s, path, { view = "top" })
    expect_error({ "view direction must be horizontal" }, ashlar.draw, s, path, { view = { 0, 1, 1 } })
    expect_error({ "cannot tell the format of", ".svg or .png" }, ashlar.draw, s, dir .. "/a.jpg")
    expect_error({ "the result is of a structure with 7 blocks, this one has 9" },
      ashlar.draw, models.arch{ voussoirs = 7 }, path, { result = r })
    expect_error({ "result: expected a Result of ashlar.analyze", "got Structure" },
      ashlar.draw, s, path, { result = s })
    expect_error({ "thrust needs the result" }, ashlar.draw, s, path, { thrust = true })
    expect_error({ "width: expected a positive whole number of pixels", "12.5" },
      ashlar.draw, s, path, { width = 12.5 })
    expect_error({ "width and height must lie in [100, 16384]" }, ashlar.draw, s, path, { height = 50 })
    expect_error({ "color: a list of colours needs one per block (7)" },
      ashlar.draw, s, path, { color = { { 1, 0, 0 } } })
    expect_error({ "bad argument #1", "Structure expected" }, ashlar.draw, r, path)
    assert.is_nil(io.open(path))
  end)
end)

describe("ashlar.legend", function()
  local dir
  before_each(function() dir = support.temp_folder() end)
  after_each(function() support.remove_folder(dir) end)

  it("writes vertical and horizontal colour bars with their ticks", function()
    ashlar.legend(dir .. "/v.png", { map = "viridis", range = { 0, 2.5 },
                                     label = "load capacity (x own weight)" })
    local width, height = png_size(support.read_file(dir .. "/v.png"))
    assert.equal(300, width)
    assert.equal(600, height)
    ashlar.legend(dir .. "/h.png", { map = "coolwarm", range = { -1, 1 }, orientation = "horizontal" })
    width, height = png_size(support.read_file(dir .. "/h.png"))
    assert.equal(600, width)
    assert.equal(150, height)
    ashlar.legend(dir .. "/v.svg", { range = { 0.3, 1.1 }, width = 200, height = 400, label = "tension (kN)" })
    local svg = support.read_file(dir .. "/v.svg")
    assert.is_truthy(svg:find('width="200pt"%s+height="400pt"'))
    -- Five ticks from lo to hi, evenly apart, and the label, as text.
    local texts = support.svg_texts(svg)
    for _, text in ipairs{ "0.3", "0.5", "0.7", "0.9", "1.1", "tension (kN)" } do
      assert.is_true(support.contains(texts, text), text)
    end
  end)

  it("reports bad options clearly", function()
    local path = dir .. "/l.png"
    expect_error({ "range: expected {lo, hi}" }, ashlar.legend, path, {})
    expect_error({ "range must be finite with lo < hi" }, ashlar.legend, path, { range = { 1, 0 } })
    expect_error({ "unknown colour map 'jet'", "'viridis'" }, ashlar.legend, path,
      { map = "jet", range = { 0, 1 } })
    expect_error({ "orientation: expected 'vertical' or 'horizontal'" }, ashlar.legend, path,
      { range = { 0, 1 }, orientation = "diagonal" })
    expect_error({ "unknown option 'lable'", "allowed: height, label, map, orientation, range, values, width" },
      ashlar.legend, path, { range = { 0, 1 }, lable = "x" })
    expect_error({ ".svg or .png" }, ashlar.legend, dir .. "/l.pdf", { range = { 0, 1 } })
    assert.is_nil(io.open(path))
  end)
end)
