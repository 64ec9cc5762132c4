-- Log-log charts of benchmark rows against block count, drawn by gnuplot
-- (PNG and SVG), each written to a temporary name and renamed when done.
-- Shared by the scripts that measure time against model size:
--   local log_chart = dofile(script_folder .. "/log_chart.lua")
--   log_chart.draw_all(chart, rows, folder .. "/name")   -- name.png, name.svg
-- chart = { title, ylabel, series = { { kind, column, title, style }, ... } };
-- rows: tables with `structure` (matched against kind), `blocks` and the
-- columns.
local log_chart = {}

log_chart.terminals = {
  { extension = "png", command = "set terminal pngcairo size 1000,700 font 'sans,12'" },
  { extension = "svg", command = "set terminal svg size 1000,700 dynamic font 'sans,12'" },
}

-- A log-log chart of `rows`, drawn by gnuplot into a temporary name and
-- renamed when done.
function log_chart.draw(chart, rows, path, terminal)
  local script = { terminal, ("set output %q"):format(path .. ".tmp"), ("set title %q"):format(chart.title),
    "set xlabel 'blocks'", ("set ylabel %q"):format(chart.ylabel), "set logscale xy", "set xrange [70:30000]",
    "set format x '10^{%T}'", "set format y '10^{%T}'", "set mxtics 10", "set mytics 10",
    "set grid xtics ytics mxtics mytics", "set key top left box opaque" }
  local plots = {}
  for index, line in ipairs(chart.series) do
    local points = {}
    for _, row in ipairs(rows) do
      local value = tonumber(row[line.column])
      if row.structure == line.kind and value then points[#points + 1] = row.blocks .. " " .. value end
    end
    if #points > 0 then
      script[#script + 1] = ("$series%d << EOD\n%s\nEOD"):format(index, table.concat(points, "\n"))
      plots[#plots + 1] = ("$series%d using 1:2 with linespoints lw 2 ps 1.2 %s title %q"):format(index,
        line.style, line.title)
    end
  end
  script[#script + 1] = "plot " .. table.concat(plots, ", \\\n  ")
  script[#script + 1] = "unset output"
  local gnuplot = assert(io.popen("gnuplot", "w"))
  gnuplot:write(table.concat(script, "\n"), "\n")
  assert(gnuplot:close(), "gnuplot failed on " .. path)
  assert(os.rename(path .. ".tmp", path))
end

-- The chart in every terminal: path .. ".png" and path .. ".svg".
function log_chart.draw_all(chart, rows, path)
  for _, terminal in ipairs(log_chart.terminals) do
    log_chart.draw(chart, rows, path .. "." .. terminal.extension, terminal.command)
  end
end

return log_chart
