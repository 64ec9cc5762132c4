-- Helpers shared by the scripts in this folder (found on package.path
-- through the script's own folder): atomic writes and gnuplot charts.
local support = {}

-- Quotes a string for the shell.
function support.shell_quoted(text)
  return "'" .. text:gsub("'", "'\\''") .. "'"
end

-- Writes `text` to `path` through a temporary file renamed into place, so a
-- reader never sees half a file.
function support.write_atomically(path, text)
  local temporary = path .. ".tmp"
  local file = assert(io.open(temporary, "w"))
  assert(file:write(text))
  assert(file:close())
  assert(os.rename(temporary, path))
end

-- Draws a chart with gnuplot into `base`.png and `base`.svg (1000 x 700),
-- each under a temporary name renamed when gnuplot has finished it.
-- `commands` is the gnuplot script after the terminal and output lines.
function support.chart(base, commands)
  local script = {
    'if (strstrt(GPVAL_TERMINALS, "pngcairo") > 0) {',
    '  set terminal pngcairo size 1000,700 font "Sans,11"',
    '} else {',
    '  set terminal png size 1000,700',
    '}',
    ("set output %q"):format(base .. ".png.tmp"),
    commands,
    'set terminal svg size 1000,700 dynamic font "Sans,11"',
    ("set output %q"):format(base .. ".svg.tmp"),
    "replot",
    "set output",
  }
  local gnuplot = assert(io.popen("gnuplot", "w"))
  gnuplot:write(table.concat(script, "\n"), "\n")
  assert(gnuplot:close(), "gnuplot failed on the chart " .. base)
  assert(os.rename(base .. ".png.tmp", base .. ".png"))
  assert(os.rename(base .. ".svg.tmp", base .. ".svg"))
end

return support
