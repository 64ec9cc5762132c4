-- ashlar.export to the HTML viewer, as a script calls it: by extension or
-- format = "html", what the page holds, and the errors of its options.
-- (The page in a browser: tests/tools/check_viewer.js, ctest viewer.*.)
local ashlar = require "ashlar"
local models = require "ashlar.models"
local support = require "spec_support"
local expect_error = support.expect_error

local function read(path)
  local file = assert(io.open(path, "rb"))
  local text = file:read("a")
  file:close()
  return text
end

-- The page's scene, the JSON text of its ashlar-scene element.
local function scene_of(path)
  return read(path):match('<script type="application/json" id="ashlar%-scene">(.-)</script>')
end

describe("ashlar.export to HTML", function()
  local s = models.arch{ voussoirs = 5 }
  local r = ashlar.analyze(s, { friction = 0.7 })
  local folder = os.tmpname()
  os.remove(folder)
  os.execute("mkdir " .. support.quote(folder))
  teardown(function() os.execute("rm -r " .. support.quote(folder)) end)

  it("writes one page by extension, or by format whatever the name", function()
    ashlar.export(s, folder .. "/arch.html", { result = r, forces = true, thrust = true, interfaces = true })
    ashlar.export(s, folder .. "/arch.view", { format = "html" })
    for _, name in ipairs{ "arch.html", "arch.view" } do
      local page = read(folder .. "/" .. name)
      assert.truthy(page:find("^<!DOCTYPE html>"))
      assert.is_nil(page:find("<script[^>]+src="))  -- nothing to fetch
    end
    local scene = scene_of(folder .. "/arch.html")
    assert.truthy(scene:find('"title":"arch.html"', 1, true))
    assert.truthy(scene:find('"summary":"7 blocks: stable', 1, true))
    for _, layer in ipairs{ "blocks", "interfaces", "forces", "thrust", "edges" } do
      assert.truthy(scene:find('{"name":"' .. layer .. '","visible":true}', 1, true), layer)
    end
    assert.truthy(scene:find('"name":"voussoir 3"', 1, true))
    assert.truthy(scene:find('"name":"force 3-4"', 1, true))
    assert.truthy(scene:find('"name":"thrust line"', 1, true))
    -- Without a result: blocks and their outlines only.
    local bare = scene_of(folder .. "/arch.view")
    assert.is_nil(bare:find('"name":"forces"', 1, true))
    assert.truthy(bare:find('{"name":"edges","visible":true}', 1, true))
  end)

  it("is the same page from the C module in a stock lua5.4, which carries three.js too", function()
    local module_dir = os.getenv("ASHLAR_MODULE_DIR")
    assert.is_not_nil(module_dir, "set ASHLAR_MODULE_DIR to the folder of ashlar.so")
    local write = 'local ashlar = require "ashlar" local models = require "ashlar.models" '
                  .. ('ashlar.export(models.arch{ voussoirs = 5 }, %q)'):format(folder .. "/module.html")
    assert.is_true(os.execute("lua5.4 -e " .. support.quote(("package.cpath = %q .. ';' .. package.cpath")
                                  :format(module_dir .. "/?.so")) .. " -e " .. support.quote(write)))
    ashlar.export(models.arch{ voussoirs = 5 }, folder .. "/host.html")
    local from_module, from_host = read(folder .. "/module.html"), read(folder .. "/host.html")
    assert.truthy(from_module:find('"three.core":"', 1, true))
    -- Alike but for the title, the file's name.
    assert.is_true(from_host:gsub("host%.html", "module.html") == from_module)
  end)

  it("labels a legend for colours mapped from values, and titles the page", function()
    local values = {}
    for i = 1, #s do values[i] = i end
    ashlar.export(s, folder .. "/values.html", { color = { values = values, map = "magma", range = { 0, 10 } },
                                                  legend = "index", title = "five voussoirs", edges = false })
    local scene = scene_of(folder .. "/values.html")
    assert.truthy(scene:find('"title":"five voussoirs"', 1, true))
    assert.truthy(scene:find('"legend":{"label":"index","lo":"0","hi":"10"', 1, true))
    assert.truthy(scene:find('["index","3"]', 1, true))  -- voussoir 3's read-out
    -- Without a range, values none of which is negative map from 0 (a
    -- magnitude's legend starts at nothing); a negative one keeps its own.
    ashlar.export(s, folder .. "/from0.html", { color = { values = values }, legend = "index" })
    assert.truthy(scene_of(folder .. "/from0.html"):find('"legend":{"label":"index","lo":"0","hi":"' .. #s .. '"', 1, true))
    values[1] = -2
    ashlar.export(s, folder .. "/signed.html", { color = { values = values }, legend = "index" })
    assert.truthy(scene_of(folder .. "/signed.html"):find('"legend":{"label":"index","lo":"-2","hi":"' .. #s .. '"', 1, true))
    assert.truthy(scene:find('{"name":"edges","visible":false}', 1, true))
    assert.truthy(read(folder .. "/values.html"):find("<title>five voussoirs</title>", 1, true))
  end)

  it("switches cables, load traces and a mechanism's displaced blocks like the mesh files draw them", function()
    local bridge = models.cable_stayed_bridge{}
    ashlar.export(bridge, folder .. "/bridge.html")
    assert.truthy(scene_of(folder .. "/bridge.html"):find('{"name":"cables","visible":true}', 1, true))
    local frame = models.h_frame{}
    ashlar.export(frame, folder .. "/traces.html", { traces = ashlar.trace_loads(frame, "beam", { traces = 5, seed = 1 }) })
    local traces = scene_of(folder .. "/traces.html")
    assert.truthy(traces:find('{"name":"traces","visible":true}', 1, true))
    assert.truthy(traces:find('"name":"load traces"', 1, true))
    local thin = models.arch{ voussoirs = 5, thickness = 0.2 }
    local falls = ashlar.analyze(thin, { friction = 0.7 })
    assert.is_false(falls.stable)
    ashlar.export(thin, folder .. "/falls.html", { result = falls, mechanism = 0.3, title = "thin" })
    ashlar.export(thin, folder .. "/stands.html", { result = falls, title = "thin" })
    local moved, still = scene_of(folder .. "/falls.html"), scene_of(folder .. "/stands.html")
    assert.truthy(moved:find('"summary":"7 blocks: unstable, infeasibility ', 1, true))
    -- The free blocks and their outlines moved, and nothing else changed.
    local function without_geometry(scene) return (scene:gsub('"positions":%b[]', ""):gsub('"outline":%b[]', "")) end
    assert.are_not.equal(still, moved)
    assert.are.equal(without_geometry(still), without_geometry(moved))
  end)

  it("names the option at fault", function()
    expect_error({ 'format: expected "compas" or "html"', 'got "htm"' }, ashlar.export, s, folder .. "/x.html",
                 { format = "htm" })
    expect_error({ "legend: \"height\" labels colours mapped from values" }, ashlar.export, s,
                 folder .. "/x.html", { legend = "height", color = { 0.5, 0.5, 0.5 } })
    expect_error({ "legend: only the HTML viewer" }, ashlar.export, s, folder .. "/x.glb", { legend = "height" })
    expect_error({ "title: only the HTML viewer" }, ashlar.export, s, folder .. "/x.glb", { title = "arch" })
    expect_error({ "title: does not apply to a COMPAS assembly" }, ashlar.export, s, folder .. "/x.json",
                 { title = "arch" })
    expect_error({ "legend: expected a string" }, ashlar.export, s, folder .. "/x.html", { legend = 3 })
    expect_error({ "forces needs the result of an analysis" }, ashlar.export, s, folder .. "/x.html",
                 { forces = true })
    expect_error({ "unknown option 'colour'" }, ashlar.export, s, folder .. "/x.html", { colour = { 1, 0, 0 } })
    assert.is_nil(io.open(folder .. "/x.html"))
  end)
end)
