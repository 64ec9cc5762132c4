-- Log-log charts of benchmark rows against block count, drawn by
-- ashlar.chart (PNG and SVG). Shared by the scripts that measure time
-- against model size:
--   local log_chart = dofile(script_folder .. "/log_chart.lua")
--   log_chart.draw_all(chart, rows, folder .. "/name")   -- name.png, name.svg
-- chart = { title, ylabel, series = { { kind, column, title }, ... } };
-- rows: tables with `structure` (matched against kind), `blocks` and the
-- columns. Each series is one line, named by its title.
local support = require "script_support"

local log_chart = {}

-- The chart as name.png and name.svg.
function log_chart.draw_all(chart, rows, path)
  -- One row per point, with the series' title as its y column: ashlar.chart
  -- draws one line per y column and leaves each row out of the lines whose
  -- column it lacks.
  local points, titles = {}, {}
  for _, line in ipairs(chart.series) do
    local count = #points
    for _, row in ipairs(rows) do
      local value = tonumber(row[line.column])
      if row.structure == line.kind and value then
        points[#points + 1] = { blocks = tonumber(row.blocks), [line.title] = value }
      end
    end
    -- A series without values (cvxopt not run, say) is left out.
    if #points > count then titles[#titles + 1] = line.title end
  end
  support.chart(path, { data = points, x = "blocks", y = titles, title = chart.title, y_label = chart.ylabel,
                        log_x = true, log_y = true })
end

return log_chart
