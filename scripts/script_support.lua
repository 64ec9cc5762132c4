-- Helpers shared by the scripts in this folder (found on package.path
-- through the script's own folder): atomic writes, CSV and charts.
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

-- The folders a figure script writes to: arg[1] (default `default_folder`)
-- for its pictures, arg[2] (default a new temporary folder) for the HTML
-- pages it screenshots; both created.
function support.output_folders(default_folder)
  local folder, pages = arg[1] or default_folder, arg[2]
  if not pages then
    pages = os.tmpname()
    os.remove(pages)
  end
  support.make_folders(folder, pages)
  return folder, pages
end

function support.write_atomically(path, text)
  local temporary = path .. ".tmp"
  local file = assert(io.open(temporary, "w"))
  assert(file:write(text))
  assert(file:close())
  assert(os.rename(temporary, path))
end

-- Draws a chart with ashlar.chart into `base`.png and `base`.svg, 1000 x 700
-- (each written whole by ashlar.chart). `options` are ashlar.chart's but
-- `path`.
function support.chart(base, options)
  local ashlar = require "ashlar"
  for _, extension in ipairs{ "png", "svg" } do
    local full = { path = base .. "." .. extension, width = 1000, height = 700 }
    for key, value in pairs(options) do full[key] = value end
    ashlar.chart(full)
  end
end

-- The rows of a CSV file that this folder's scripts wrote (a header line,
-- then comma-separated values without quotes): one table per line from
-- column names to values, numbers where they read as numbers, "true" and
-- "false" as booleans, empty fields nil.
function support.read_csv(path)
  local file = assert(io.open(path))
  local header, rows = nil, {}
  for line in file:lines() do
    local fields = {}
    for field in (line .. ","):gmatch("([^,]*),") do fields[#fields + 1] = field end
    if not header then
      header = fields
    else
      local row = {}
      for k, name in ipairs(header) do
        local field = fields[k]
        if field == "true" or field == "false" then
          row[name] = field == "true"
        elseif field ~= nil and field ~= "" then
          row[name] = tonumber(field) or field
        end
      end
      rows[#rows + 1] = row
    end
  end
  file:close()
  return rows
end

-- Whether the script was asked only to draw its charts again from the CSV
-- it wrote before (the argument "--charts", anywhere; it is taken out of
-- `arg`, so the other arguments keep their places).
function support.charts_only()
  for k = #arg, 1, -1 do
    if arg[k] == "--charts" then
      table.remove(arg, k)
      return true
    end
  end
  return false
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
