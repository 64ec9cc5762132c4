-- ashlar.chart: result columns of parametric studies plotted against
-- parameters.
local ashlar = require "ashlar"

local support = require "spec_support"
local expect_error = support.expect_error
local svg_texts, contains = support.svg_texts, support.contains

local PNG_SIGNATURE = "\137PNG\r\n\26\n"

-- Width and height of a PNG from its IHDR chunk.
local function png_size(data)
  return string.unpack(">I4I4", data, 17)
end

-- A study as parametric runs give it: for n = 16, 8 (in that order) and
-- t = 0.08 ... 0.12, one row each; the runs at t = 0.09 failed (no
-- infeasibility, no stable).
local function study()
  local rows = {}
  for _, n in ipairs{ 16, 8 } do
    for k = 0, 4 do
      local t = 0.08 + 0.01 * k
      local row = { t = t, n = n, mu = 0.5, status = "ok" }
      if k == 1 then
        row.status = "failed"
      else
        row.infeasibility = math.max(0, 0.1 - t) * 16 / n
        row.stable = row.infeasibility == 0
      end
      rows[#rows + 1] = row
    end
  end
  return rows
end

-- The Okabe-Ito colours of the first three series, as the SVG writes them.
local SERIES_COLORS = { "#0072B2", "#D55E00", "#009E73" }

local function names(result)
  local list = {}
  for k, series in ipairs(result.series) do list[k] = series.name end
  return list
end

local function entries(dir)
  local listing = io.popen("ls -A " .. support.quote(dir))
  local list = {}
  for name in listing:lines() do list[#list + 1] = name end
  listing:close()
  return list
end

describe("ashlar.chart", function()
  local dir
  before_each(function() dir = support.temp_folder() end)
  after_each(function() support.remove_folder(dir) end)

  it("plots a column against a parameter, one line per series value", function()
    local path = dir .. "/study.png"
    local r = ashlar.chart{ path = path, data = study(), x = "t", y = "infeasibility", series = "n" }
    assert.equal(path, r.path)
    -- Numeric order: 8 before 16, whatever the rows' order.
    assert.same({ "n = 8", "n = 16" }, names(r))
    assert.equal(4, r.series[1].points)
    assert.equal(4, r.series[2].points)
    assert.equal(2, r.skipped)
    local png = support.read_file(path)
    assert.equal(PNG_SIGNATURE, png:sub(1, 8))
    local width, height = png_size(png)
    assert.equal(900, width)
    assert.equal(600, height)
    assert.same({ "study.png" }, entries(dir))
  end)

  it("names lines after the y columns, or after the y and series columns", function()
    local r = ashlar.chart{ path = dir .. "/one.png", data = study(), x = "t", y = "infeasibility" }
    assert.same({ "infeasibility" }, names(r))
    assert.equal(8, r.series[1].points)
    r = ashlar.chart{ path = dir .. "/two.png", data = study(), x = "t", y = { "infeasibility", "stable" } }
    assert.same({ "infeasibility", "stable" }, names(r))
    r = ashlar.chart{ path = dir .. "/four.png", data = study(), x = "t", y = { "infeasibility", "stable" },
                      series = { "n", "mu" } }
    assert.same({ "infeasibility, n = 8, mu = 0.5", "infeasibility, n = 16, mu = 0.5",
                  "stable, n = 8, mu = 0.5", "stable, n = 16, mu = 0.5" }, names(r))
    assert.equal(2, r.skipped)
    -- Booleans, strings and missing values split series too.
    r = ashlar.chart{ path = dir .. "/status.png", data = study(), x = "t", y = "n", series = "stable" }
    assert.same({ "stable = false", "stable = true", "stable = nil" }, names(r))
    -- Stable from t = 0.1 on: 3 of the 4 runs that finished, for each n.
    assert.same({ 2, 6, 2 }, { r.series[1].points, r.series[2].points, r.series[3].points })
    assert.equal(0, r.skipped)
    r = ashlar.chart{ path = dir .. "/status.png", data = study(), x = "t", y = "n", series = "status" }
    assert.same({ "status = failed", "status = ok" }, names(r))
  end)

  it("plots booleans as 0 and 1", function()
    local rows = study()
    -- stable is false (0) at t = 0.08: not on a log axis.
    expect_error({ "chart: log_y takes values > 0 only, got series 'stable' point 1 (x = 0.08, y = 0)" },
      ashlar.chart, { path = dir .. "/log.png", data = rows, x = "t", y = "stable", log_y = true })
    -- true is 1: fine on a log axis.
    local stable = {}
    for _, row in ipairs(rows) do
      if row.stable then stable[#stable + 1] = row end
    end
    local r = ashlar.chart{ path = dir .. "/log.png", data = stable, x = "t", y = "stable", log_y = true }
    assert.equal(6, r.series[1].points)
    -- A boolean x column works as well.
    r = ashlar.chart{ path = dir .. "/x.png", data = rows, x = "stable", y = "t" }
    assert.equal(8, r.series[1].points)
  end)

  it("writes SVG and PDF at the asked size, in every kind", function()
    for _, kind in ipairs{ "lines", "points", "linespoints", "steps" } do
      ashlar.chart{ path = dir .. "/" .. kind .. ".svg", data = study(), x = "t", y = "infeasibility",
                    series = "n", kind = kind, width = 640, height = 480, title = kind,
                    x_label = "t / R", y_label = "tension / weight" }
      local svg = support.read_file(dir .. "/" .. kind .. ".svg")
      assert.equal("<?xml", svg:sub(1, 5))
      assert.is_truthy(svg:find('<svg[^>]*width="640pt"%s+height="480pt"'))
      -- The title, the axis labels and both lines' legend entries are text.
      local texts = svg_texts(svg)
      for _, text in ipairs{ kind, "t / R", "tension / weight", "n = 8", "n = 16" } do
        assert.is_true(contains(texts, text), text)
      end
      -- Two lines: the first two series colours, not the third.
      assert.is_truthy(svg:find(SERIES_COLORS[1], 1, true))
      assert.is_truthy(svg:find(SERIES_COLORS[2], 1, true))
      assert.is_falsy(svg:find(SERIES_COLORS[3], 1, true))
    end
    ashlar.chart{ path = dir .. "/c.pdf", data = study(), x = "t", y = "infeasibility", log_x = true,
                  width = 500, height = 300 }
    local pdf = support.read_file(dir .. "/c.pdf")
    assert.equal("%PDF", pdf:sub(1, 4))
    assert.is_truthy(pdf:find("/MediaBox [ 0 0 500 300 ]", 1, true))
    ashlar.chart{ path = dir .. "/small.png", data = study(), x = "t", y = "infeasibility",
                  width = 200, height = 16384 }
    local width, height = png_size(support.read_file(dir .. "/small.png"))
    assert.equal(200, width)
    assert.equal(16384, height)
  end)

  it("takes the axes' ends from x_range and y_range, cutting off what lies outside", function()
    local r = ashlar.chart{ path = dir .. "/range.svg", data = study(), x = "t", y = "infeasibility", series = "n",
                            x_range = { 0.1, 0.2 }, y_range = { -1, 1 }, kind = "points" }
    assert.equal(4, r.series[1].points)
    local svg = support.read_file(dir .. "/range.svg")
    local texts = svg_texts(svg)
    assert.is_true(contains(texts, "0.10"))
    assert.is_true(contains(texts, "0.20"))
    assert.is_true(contains(texts, "-1.0"))
    assert.is_false(contains(texts, "0.08"))
    -- Of each line's markers only those at t = 0.1 .. 0.12 are drawn (3 + 3
    -- of 8), plus one per legend entry.
    local markers = 0
    for _ in svg:gmatch("&#x25cf;") do markers = markers + 1 end
    for _ in svg:gmatch("&#x25a0;") do markers = markers + 1 end
    assert.equal(3 + 3 + 2, markers)
  end)

  it("labels log axes at their decades", function()
    local rows = {}
    for k = 0, 3 do rows[#rows + 1] = { blocks = 10 ^ (k + 1), seconds = 10 ^ (2 * k - 4) } end
    ashlar.chart{ path = dir .. "/log.svg", data = rows, x = "blocks", y = "seconds", log_x = true, log_y = true }
    local texts = svg_texts(support.read_file(dir .. "/log.svg"))
    for exponent = 1, 4 do assert.is_true(contains(texts, "10^" .. exponent), "x: 10^" .. exponent) end
    for exponent = -4, 2 do assert.is_true(contains(texts, "10^" .. exponent), "y: 10^" .. exponent) end
    assert.is_false(contains(texts, "10^5"))
  end)

  it("reports bad options and data clearly, and writes nothing", function()
    local rows = study()
    local path = dir .. "/c.png"
    local function chart(options)
      local full = { path = path, data = rows, x = "t", y = "infeasibility" }
      for key, value in pairs(options) do full[key] = value end
      return ashlar.chart(full)
    end
    expect_error({ "bad argument #1", "expected an option table" }, ashlar.chart, path)
    expect_error({ "bad argument #1", "unknown option 'colour'", "(allowed: boundary, curves, data, height, kind, levels, "
                   .. "log_x, log_y, map, path, series, title, width, x, x_label, x_range, y, y_label, y_range, z, "
                   .. "z_label)" }, chart,
                 { colour = "red" })
    expect_error({ "x_range: expected {lo, hi}, got number" }, chart, { x_range = 1 })
    expect_error({ "chart: y_range must be finite with lo < hi, got {2, 1}" }, chart, { y_range = { 2, 1 } })
    expect_error({ "chart: y_range must be finite with lo < hi and lo > 0 (log axis), got {0, 1}" }, chart,
      { y_range = { 0, 1 }, log_y = true, data = { { t = 1, infeasibility = 1 } } })
    expect_error({ "bad argument #1", "path: required, the file to write (.png, .svg or .pdf)" },
      ashlar.chart, { data = rows, x = "t", y = "infeasibility" })
    expect_error({ "data: required, a list of row tables" }, ashlar.chart, { path = path, x = "t", y = "n" })
    expect_error({ "data: expected a list of row tables, got string" }, chart, { data = "rows" })
    expect_error({ "data[2]: expected a row table, got number" }, chart, { data = { { t = 1 }, 5 } })
    expect_error({ "x: required, the column plotted along x" }, ashlar.chart,
      { path = path, data = rows, y = "n" })
    expect_error({ "y: required, a column or a list of columns" }, ashlar.chart,
      { path = path, data = rows, x = "t" })
    expect_error({ "y: expected a column name or a list of them, got an empty table" }, chart, { y = {} })
    expect_error({ "y[2]: expected a column name, got number" }, chart, { y = { "n", 3 } })
    expect_error({ "series: expected a column name or a list of them, got boolean" }, chart, { series = true })
    expect_error({ "cannot tell the format of", "use .png, .svg or .pdf" }, chart, { path = dir .. "/c.jpg" })
    expect_error({ "chart: x: no row has a column 'tt' (columns: infeasibility, mu, n, stable, status, t)" },
      chart, { x = "tt" })
    expect_error({ "chart: y: no row has a column 'infeasability'" }, chart, { y = "infeasability" })
    expect_error({ "chart: series: no row has a column 'N'" }, chart, { series = "N" })
    expect_error({ "chart: y: row 1 has a string (\"ok\") in column 'status'; plotted columns take numbers "
                   .. "or booleans" }, chart, { y = "status" })
    expect_error({ "chart: x: row 2 has a table in column 't'" }, chart,
      { data = { { t = 1, infeasibility = 0 }, { t = {}, infeasibility = 0 } } })
    expect_error({ "chart: series: row 1 has a function in column 'f'" }, chart,
      { data = { { t = 1, infeasibility = 0, f = print } }, series = "f" })
    -- Points whose x or y is not finite are skipped and counted.
    local elsewhere = os.tmpname() .. ".png"
    local skipping = ashlar.chart{ path = elsewhere, x = "t", y = "infeasibility",
      data = { { t = 1, infeasibility = 0 }, { t = 2, infeasibility = math.huge }, { t = 0 / 0, infeasibility = 0 },
               { t = 3, infeasibility = 1 } } }
    os.remove(elsewhere)
    assert.equal(2, skipping.skipped)
    assert.equal(2, skipping.series[1].points)
    expect_error({ "chart: series: row 1 has mu = nan" }, chart,
      { data = { { t = 1, infeasibility = 0, mu = 0 / 0 } }, series = "mu" })
    expect_error({ "chart: log_x takes values > 0 only, got series 'infeasibility' point 1 (x = -1, y = 0)" },
      chart, { data = { { t = -1, infeasibility = 0 }, { t = 1, infeasibility = 1 } }, log_x = true })
    expect_error({ "chart: nothing to plot: no row has both x ('t') and y ('infeasibility'); 3 rows skipped" },
      chart, { data = { { t = 1, status = "failed" }, { t = 2, infeasibility = nil, n = 4 }, { infeasibility = 1 } } })
    expect_error({ "chart: nothing to plot: data has no rows" }, chart, { data = {} })
    expect_error({ "chart: width and height must lie in [200, 16384], got 100 x 600" }, chart, { width = 100 })
    expect_error({ "chart: width and height must lie in [200, 16384], got 900 x 20000" }, chart, { height = 20000 })
    expect_error({ "width: expected a positive whole number of pixels, got 640.5" }, chart, { width = 640.5 })
    expect_error({ "chart: unknown kind 'bars' (allowed: lines, points, linespoints, steps, map)" }, chart,
      { kind = "bars" })
    expect_error({ "log_y: expected a boolean, got string" }, chart, { log_y = "yes" })
    expect_error({ "title: expected a string, got number" }, chart, { title = 3 })
    assert.same({}, entries(dir))
  end)

  it("leaves an existing file as it was when it fails", function()
    local path = dir .. "/c.svg"
    support.write_file(path, "old")
    expect_error({ "log_y takes values > 0 only" }, ashlar.chart,
      { path = path, data = study(), x = "t", y = "infeasibility", log_y = true })
    assert.equal("old", support.read_file(path))
    ashlar.chart{ path = path, data = study(), x = "t", y = "infeasibility" }
    assert.equal("<?xml", support.read_file(path):sub(1, 5))
    assert.same({ "c.svg" }, entries(dir))
  end)
end)
