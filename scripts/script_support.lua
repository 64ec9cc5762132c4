-- Helpers shared by the scripts in this folder (found on package.path
-- through the script's own folder): atomic writes and gnuplot charts.
local support = {}

-- Quotes a string for the shell.
function support.shell_quoted(text)
  return "'" .. text:gsub("'", "'\\''") .. "'"
end

-- Writes `text` to `path` through a temporary file renamed into place, so a
-- reader never sees half a file.
-- Creates each folder (and its parents) unless it exists; an error names it.
function support.make_folders(...)
  for _, folder in ipairs({ ... }) do
    assert(os.execute("mkdir -p " .. support.shell_quoted(folder)), "cannot create " .. folder)
  end
end

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

-- Whether PNG renderings of 3D files can be made (Debian: f3d xvfb).
function support.can_render()
  local function exists(command) return os.execute("command -v " .. command .. " > /dev/null 2>&1") end
  return exists("f3d") and exists("xvfb-run")
end

-- Renders glb into the PNG of the same name with f3d, the camera turned
-- from the front (the x-z plane seen from -y) by view.azimuth and
-- view.elevation (degrees); written under a temporary name, then renamed.
function support.render(glb, view)
  local png = glb:gsub("%.glb$", ".png")
  local temporary = png .. ".tmp.png"
  local command = table.concat({
    "xvfb-run -a -s '-screen 0 1024x768x24' f3d", support.shell_quoted(glb),
    "--output", support.shell_quoted(temporary), "--resolution 1000,700 --bg-color 1,1,1 --fxaa",
    "--camera-azimuth-angle", tostring(view.azimuth), "--camera-elevation-angle", tostring(view.elevation),
    "> /dev/null 2>&1",
  }, " ")
  assert(os.execute(command), "f3d failed: " .. command)
  assert(os.rename(temporary, png))
end

-- Runs f, prints `what` with the seconds it took, returns f's result.
function support.timed(what, f)
  local clock = require("ashlar").clock
  local start = clock()
  local result = f()
  print(("  %-32s %8.3f s"):format(what, clock() - start))
  return result
end

-- Whether pages of the HTML viewer can be photographed (Debian: chromium).
function support.can_screenshot()
  return os.execute("command -v chromium > /dev/null 2>&1")
end

-- Photographs the page `html` into `png` (width x height pixels) with
-- headless chromium, WebGL on SwiftShader (no GPU or display needed;
-- --no-sandbox for containers), once the page has had 10 s of virtual time
-- to draw; written under a temporary name, then renamed.
function support.screenshot(html, png, width, height)
  local temporary = png .. ".tmp.png"
  local command = table.concat({
    "chromium --headless --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --hide-scrollbars",
    ("--window-size=%d,%d"):format(width, height), "--virtual-time-budget=10000",
    "--screenshot=" .. support.shell_quoted(temporary), support.shell_quoted("file://" .. html),
    "> /dev/null 2>&1",
  }, " ")
  assert(os.execute(command), "chromium failed: " .. command)
  assert(os.rename(temporary, png))
end

return support
