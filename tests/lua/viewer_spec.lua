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
    ashlar.export(thin, folder .. "/stands.html", { result = falls, mechanism = false, title = "thin" })
    local moved, still = scene_of(folder .. "/falls.html"), scene_of(folder .. "/stands.html")
    assert.truthy(moved:find('"summary":"7 blocks: unstable, infeasibility ', 1, true))
    -- The page plays the mechanism: the blocks drawn where they stand (the
    -- still's objects), moved by the player, the fastest centroid 0.3 m.
    assert.truthy(still:find('"animation":null', 1, true))
    assert.truthy(moved:find('"start":1.0,"mechanism":0.3}', 1, true))
    assert.truthy(moved:find("the fastest block's centroid moved 0.3 m at its extreme", 1, true))
    local function objects(scene) return scene:match('"objects":(%b[])') end
    assert.are.equal(objects(still), objects(moved))
  end)

  it("plays a load factor's mechanism: each block moved rigidly by its virtual motion", function()
    local arch = models.arch{ radius = 1, thickness = 0.15, voussoirs = 16 }
    local f = ashlar.load_factor(arch, { friction = math.huge })
    ashlar.export(arch, folder .. "/mechanism.html", { result = f, mechanism = 0.2, autoplay = false })
    local json = scene_of(folder .. "/mechanism.html")
    assert.truthy(json:find('"autoplay":false', 1, true))
    -- The equilibrium at the factor is at its limit: the summary says so
    -- with the factor, not "stable".
    assert.truthy(json:find(('"summary":"%d blocks: at its limit, load factor %.4g'):format(#arch, f.factor), 1, true))
    local function numbers(text)
      local list = {}
      for number in text:gmatch("[-%d.eE+]+") do list[#list + 1] = tonumber(number) end
      return list
    end
    -- One track per free block, in block order: rest, the extreme (its
    -- centroid moved by 0.2 x its velocity in f.mechanism), rest.
    local tracks = {}
    for centroid, positions in json:match('"tracks":(%b[])'):gmatch('"centroid":(%b[]),"outline":%b[],"positions":(%b[])') do
      tracks[#tracks + 1] = { centroid = numbers(centroid), positions = numbers(positions) }
    end
    local k = 0
    for i = 1, #arch do
      if not arch:is_support(i) then
        k = k + 1
        local c, v, track = arch:block(i):centroid(), f.mechanism[i].velocity, tracks[k]
        for axis = 1, 3 do
          assert.near(c[axis], track.positions[axis], 1e-6)
          assert.near(c[axis] + 0.2 * v[axis], track.positions[3 + axis], 1e-6)
          assert.near(c[axis], track.positions[6 + axis], 1e-6)
        end
      end
    end
    assert.are.equal(k, #tracks)
    -- The hinges move with their blocks: each is in a track's objects.
    assert.truthy(json:find('"name":"hinge ', 1, true))
  end)

  it("draws a vault's thrust as a network and an arch's as a line, and forces at vertices with friction", function()
    local dome = models.dome{ meridians = 8, parallels = 4 }
    local rd = ashlar.analyze(dome, { friction = 0.7 })
    ashlar.export(dome, folder .. "/dome.html", { result = rd, thrust = true, forces = "vertices" })
    local page = scene_of(folder .. "/dome.html")
    assert.truthy(page:find('"name":"thrust network"', 1, true))
    assert.truthy(page:find('"tubes":[', 1, true))
    assert.is_nil(page:find('"name":"thrust line"', 1, true))
    assert.truthy(page:find('"name":"force %d+%-%d+ vertex 1"'))
    assert.truthy(page:find('"name":"friction %d+%-%d+ vertex %d"'))
    for _, label in ipairs{ "compression", "friction", "thrust network (thickness: force)" } do
      assert.truthy(page:find('{"label":"' .. label .. '"', 1, true), label)
    end
    -- The mesh files get the same objects.
    ashlar.export(dome, folder .. "/dome.obj", { result = rd, thrust = true, forces = "vertices" })
    local obj = read(folder .. "/dome.obj")
    assert.truthy(obj:find("thrust network", 1, true))
    assert.truthy(obj:find("friction %d+%-%d+ vertex %d"))
    -- An arch not flagged planar still has a line: its joints face one plane.
    ashlar.export(s, folder .. "/line.html", { result = r, thrust = true, forces = "resultants" })
    local line = scene_of(folder .. "/line.html")
    assert.truthy(line:find('"name":"thrust line"', 1, true))
    assert.truthy(line:find('"name":"force 3-4"', 1, true))
    assert.is_nil(line:find('"label":"friction"', 1, true))
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
    expect_error({ "forces: 'vertex' is not one of" }, ashlar.export, s, folder .. "/x.html",
                 { result = r, forces = "vertex" })
    expect_error({ "forces: expected true, false or one of", "got number" }, ashlar.export, s,
                 folder .. "/x.html", { result = r, forces = 1 })
    expect_error({ "autoplay: applies to a page (.html) that plays a collapse mechanism", "got false" },
                 ashlar.export, s, folder .. "/x.html", { result = r, autoplay = false })
    expect_error({ "mechanism: expected a distance >= 0 (m) or false, got true" }, ashlar.export, s,
                 folder .. "/x.html", { result = r, mechanism = true })
    assert.is_nil(io.open(folder .. "/x.html"))
  end)
end)
