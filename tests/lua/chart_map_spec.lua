-- ashlar.chart{ kind = "map" } (stability maps), charts of booleans and of
-- series without a finite value, and colour legends from values.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local support = require "spec_support"
local expect_error = support.expect_error
local svg_texts, contains = support.svg_texts, support.contains

-- The polylines an SVG draws in `color` ("#000000"), as lists of {x, y}
-- in the image's coordinates (y down); PLplot's SVG device draws with y up
-- under a flip of the page's height.
local function svg_polylines(svg, color)
  local height = tonumber(svg:match('viewBox="0 0 [%d.]+ ([%d.]+)"'))
  local lines = {}
  for body in svg:gmatch("<polyline(.-)/>") do
    if body:find('stroke="' .. color .. '"', 1, true) then
      local line = {}
      for x, y in body:match('points="([^"]*)"'):gmatch("([%d.%-]+),([%d.%-]+)") do
        line[#line + 1] = { tonumber(x), height - tonumber(y) }
      end
      lines[#lines + 1] = line
    end
  end
  return lines
end

-- A point of the image in data units, by the plot area and the axes' ranges
-- that ashlar.chart returns.
local function to_data(chart, p)
  local plot = chart.plot
  local fx = (p[1] - plot.left) / plot.width
  local fy = (plot.top + plot.height - p[2]) / plot.height
  return { chart.x_range[1] + fx * (chart.x_range[2] - chart.x_range[1]),
           chart.y_range[1] + fy * (chart.y_range[2] - chart.y_range[1]) }
end

-- Where the boundary (polylines in data units) crosses the line
-- coordinate `axis` (1: x, 2: y) = value: the other coordinate of each
-- segment that spans it along `axis` and is parallel to the other one.
local function crossings(lines, axis, value)
  local other = 3 - axis
  local found = {}
  for _, line in ipairs(lines) do
    for k = 2, #line do
      local a, b = line[k - 1], line[k]
      local lo, hi = math.min(a[axis], b[axis]), math.max(a[axis], b[axis])
      if lo < value and value < hi and math.abs(a[other] - b[other]) < 1e-9 then
        found[#found + 1] = a[other]
      end
    end
  end
  return found
end

-- The largest value of list below v and the smallest above it.
local function bracket(list, v)
  local below, above = -math.huge, math.huge
  for _, u in ipairs(list) do
    if u < v then below = math.max(below, u) elseif u > v then above = math.min(above, u) end
  end
  return below, above
end

local function arch(t)
  return models.arch{ radius = 1, thickness = t, voussoirs = 16 }
end

describe("ashlar.chart kind = map", function()
  it("draws the stability map of a 16-voussoir arch, its boundary where the margins put it", function()
    -- t/R × μ, rows in no particular order (μ descending).
    local ts, mus = ashlar.range(0.09, 0.125, 8), ashlar.range(0.2, 0.6, 6)
    local rows = {}
    for j = #mus, 1, -1 do
      for _, t in ipairs(ts) do
        local r = ashlar.analyze(arch(t), { friction = mus[j] })
        rows[#rows + 1] = { t = t, mu = mus[j], stable = r.stable }
      end
    end
    local dir = support.temp_folder()
    local path = dir .. "/map.svg"
    local c = ashlar.chart{ path = path, data = rows, x = "t", y = "mu", z = "stable", kind = "map",
                            x_label = "t / R", y_label = "μ" }
    assert.equal(48, c.cells)
    assert.equal(0, c.no_data)
    assert.same({ 0, 1 }, c.range)
    -- The axes end at the outer cells' edges, half a step beyond the grid.
    assert.near(0.0875, c.x_range[1], 1e-12)
    assert.near(0.1275, c.x_range[2], 1e-12)
    local svg = support.read_file(path)
    local drawn = {}
    for _, line in ipairs(svg_polylines(svg, "#000000")) do
      local data = {}
      for _, p in ipairs(line) do data[#data + 1] = to_data(c, p) end
      drawn[#drawn + 1] = data
    end
    assert.is_true(#drawn >= 1)
    -- The SVG's coordinates have two decimals: the drawn boundary is the
    -- returned one to 0.01 pt (1e-4 of the axes' ranges here).
    assert.equal(#c.boundary, #drawn)
    for k, line in ipairs(c.boundary) do
      assert.equal(#line, #drawn[k])
      for i, p in ipairs(line) do
        assert.near(p[1], drawn[k][i][1], 1e-5)
        assert.near(p[2], drawn[k][i][2], 1e-4)
      end
    end
    -- (a) At the largest μ hinging governs: the boundary crosses the top
    -- row between the grid thicknesses around the minimum thickness.
    local g = ashlar.geometric_factor(arch, 0.125, { friction = math.huge })
    assert.equal("converged", g.status)
    assert.near(0.10708, g.minimum, 2e-5)  -- DESIGN.md's value for 16 polyhedral voussoirs
    local below, above = bracket(ts, g.minimum)
    local at_top = crossings(drawn, 2, mus[#mus])
    assert.equal(1, #at_top)
    assert.is_true(below < at_top[1] and at_top[1] < above)
    -- (b) At the largest thickness sliding governs: the boundary crosses
    -- the last column between the grid μ around the friction demand.
    local d = ashlar.friction_demand(arch(ts[#ts]), { progress = false })
    assert.equal("optimal", d.status)
    local mu_below, mu_above = bracket(mus, d.friction)
    assert.is_true(mu_below > mus[1] and mu_above < math.huge)  -- the grid brackets it
    local at_right = crossings(drawn, 1, ts[#ts])
    assert.equal(1, #at_right)
    assert.is_true(mu_below < at_right[1] and at_right[1] < mu_above)
    -- The colour bar is labelled false and true, not 0 and 1.
    local texts = svg_texts(svg)
    assert.is_true(contains(texts, "false") and contains(texts, "true"))
    assert.is_false(contains(texts, "1.0"))
    support.remove_folder(dir)
  end)

  it("draws a contour of a number z where it lies, and leaves cells without data out", function()
    -- z = x + y on a 5 × 4 grid: linear, so the contour at 0.9 is x + y = 0.9.
    local rows = {}
    for _, y in ipairs{ 0.75, 0, 0.25, 0.5 } do
      for i = 0, 4 do
        local x = 0.25 * i
        rows[#rows + 1] = { x = x, y = y, z = x + y }
      end
    end
    rows[1].z = 0 / 0  -- (0, 0.75): no data
    local dir = support.temp_folder()
    local c = ashlar.chart{ path = dir .. "/z.svg", data = rows, x = "x", y = "y", z = "z", kind = "map",
                            boundary = 0.9, levels = { 0, 0.5, 1, 1.5, 2 } }
    assert.equal(1, c.no_data)
    assert.same({ 0, 2 }, c.range)
    local points = 0
    for _, line in ipairs(c.boundary) do
      for _, p in ipairs(line) do
        assert.near(0.9, p[1] + p[2], 1e-12)
        points = points + 1
      end
    end
    -- The grid lines x = 0.25 k and y = 0.25 k meet x + y = 0.9 at 7
    -- points from (0.15, 0.75) to (0.9, 0); the square x in [0, 0.25], y in
    -- [0.5, 0.75] lacks a corner, so the contour starts at (0.25, 0.65).
    assert.equal(1, #c.boundary)
    assert.equal(6, points)
    -- Continuous colours from 0 for values that are all >= 0.
    local d = ashlar.chart{ path = dir .. "/c.svg", data = rows, x = "x", y = "y", z = "z", kind = "map" }
    assert.same({ 0, 1.75 }, d.range)
    assert.same({}, d.boundary)
    support.remove_folder(dir)
  end)

  it("is what st:chart draws for a study over a grid", function()
    local study = ashlar.study{ name = "grid", params = { a = { 1, 2, 3 }, b = { 10, 20 } }, workers = 1,
                                progress = false, run = function(p) return { ok = p.a * p.b >= 40 } end }
    local dir = support.temp_folder()
    local c = study:chart{ path = dir .. "/s.png", x = "a", y = "b", z = "ok", kind = "map" }
    assert.equal(6, c.cells)
    -- ok at (2, 20) and (3, 20): the cell edges under them (y = 15) and
    -- left of (2, 20) (x = 1.5), one line through the cells' corners.
    assert.equal(1, #c.boundary)
    assert.same({ { 1.5, 25 }, { 1.5, 15 }, { 2.5, 15 }, { 3.5, 15 } }, c.boundary[1])
    support.remove_folder(dir)
  end)

  it("refuses rows that do not form a grid, naming the point", function()
    local rows = { { t = 1, mu = 1, s = true }, { t = 2, mu = 1, s = true }, { t = 1, mu = 2, s = false } }
    local opts = { path = "m.svg", data = rows, x = "t", y = "mu", z = "s", kind = "map" }
    expect_error({ "the rows do not form a grid: no row at (t = 2, mu = 2)", "2 t values × 2 mu values, 3 rows" },
                 ashlar.chart, opts)
    rows[4] = { t = 1, mu = 2, s = true }
    expect_error({ "rows 3 and 4 are both at (t = 1, mu = 2)" }, ashlar.chart, opts)
    rows[4] = { t = 2, mu = 2, s = 1 }
    expect_error({ "holds both numbers and booleans" }, ashlar.chart, opts)
    rows[4] = { t = 2, mu = 2, s = true }
    opts.levels = { 0, 1, 2 }
    expect_error({ "levels takes a z of numbers" }, ashlar.chart, opts)
    opts.levels, opts.series = nil, "t"
    expect_error({ "series: taken by line charts only" }, ashlar.chart, opts)
    opts.series, opts.kind = nil, "lines"
    expect_error({ "z: taken by kind = \"map\" only" }, ashlar.chart, opts)
  end)
end)

describe("charts of booleans and of series without a finite value", function()
  it("labels a boolean axis false and true", function()
    local rows = {}
    for k = 0, 4 do rows[#rows + 1] = { t = 0.08 + 0.01 * k, stable = k >= 2 } end
    local dir = support.temp_folder()
    ashlar.chart{ path = dir .. "/b.svg", data = rows, x = "t", y = "stable", kind = "steps" }
    local texts = svg_texts(support.read_file(dir .. "/b.svg"))
    assert.is_true(contains(texts, "false") and contains(texts, "true"))
    for _, number in ipairs{ "0.0", "0.2", "0.5", "1.0" } do assert.is_false(contains(texts, number)) end
    support.remove_folder(dir)
  end)

  it("keeps a series that is all NaN in the legend", function()
    local rows = {}
    for _, mu in ipairs{ 0.3, 0.6, 1 } do
      for k = 0, 3 do
        rows[#rows + 1] = { t = 0.1 + 0.01 * k, mu = mu, factor = mu == 0.3 and 0 / 0 or k * mu }
      end
    end
    local dir = support.temp_folder()
    local c = ashlar.chart{ path = dir .. "/n.svg", data = rows, x = "t", y = "factor", series = "mu" }
    assert.equal("mu = 0.3 (no finite value)", c.series[1].name)
    assert.equal(0, c.series[1].points)
    assert.equal(4, c.series[2].points)
    assert.equal(4, c.skipped)
    assert.is_true(contains(svg_texts(support.read_file(dir .. "/n.svg")), "mu = 0.3 (no finite value)"))
    support.remove_folder(dir)
  end)
end)

describe("colour legends of values", function()
  it("start at 0 when every value is >= 0", function()
    local dir = support.temp_folder()
    ashlar.legend(dir .. "/l.svg", { values = { 3.337e-11, 3591, 1200 }, label = "tension (N)" })
    local texts = svg_texts(support.read_file(dir .. "/l.svg"))
    assert.is_true(contains(texts, "0") and contains(texts, "3591"))
    assert.is_false(contains(texts, "3.34e-11"))
    -- Values below 0 keep their own range.
    ashlar.legend(dir .. "/m.svg", { values = { -2, 2 } })
    texts = svg_texts(support.read_file(dir .. "/m.svg"))
    assert.is_true(contains(texts, "-2") and contains(texts, "-1") and contains(texts, "2"))
    expect_error({ "values: their range [0, 0] is empty; give range = {lo, hi}" }, ashlar.legend,
                 dir .. "/z.svg", { values = { 0, 0 } })
    support.remove_folder(dir)
  end)
end)
