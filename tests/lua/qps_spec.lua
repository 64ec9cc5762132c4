-- ashlar.export_qp: the file's layout, and the same optimum from an external
-- solver (cvxopt, through tests/tools/solve_qps.py) as from ashlar.analyze.
local ashlar = require "ashlar"
local models = require "ashlar.models"

local python = "/usr/bin/python3"  -- Debian's, which has python3-cvxopt
local spec_folder = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
local solver_script = spec_folder .. "/../tools/solve_qps.py"

local support = require "spec_support"
local quote, read_file = support.quote, support.read_file

-- Runs solve_qps.py on `path`; returns its JSON's status and objective.
-- `tolerance`: cvxopt's (default 1e-10).
local function cvxopt_solution(path, tolerance)
  local pipe = assert(io.popen(("%s %s %s --tolerance %g 2>&1"):format(python, quote(solver_script), quote(path),
    tolerance or 1e-10)))
  local output = pipe:read("a")
  local ok = pipe:close()
  assert(ok, "solve_qps.py failed:\n" .. output)
  local status = output:match('"status": "([^"]*)"')
  local objective = tonumber(output:match('"objective": ([^,}]+)'))
  assert(status and objective, "unexpected output of solve_qps.py:\n" .. output)
  return status, objective
end

-- Counts in a QPS file: rows by type, distinct columns, entries per section.
local function qps_layout(text)
  local layout = { sections = {}, rows = {}, columns = 0, entries = {}, long_names = 0 }
  local section
  local seen_columns = {}
  for line in text:gmatch("[^\n]+") do
    if not line:match("^%s") then
      section = line:match("^(%S+)")
      layout.sections[#layout.sections + 1] = section
    else
      local fields = {}
      for field in line:gmatch("%S+") do fields[#fields + 1] = field end
      layout.entries[section] = (layout.entries[section] or 0) + 1
      if section == "ROWS" then
        layout.rows[fields[1]] = (layout.rows[fields[1]] or 0) + 1
        if #fields[2] > 8 then layout.long_names = layout.long_names + 1 end
      elseif section == "COLUMNS" and not seen_columns[fields[1]] then
        seen_columns[fields[1]] = true
        layout.columns = layout.columns + 1
        if #fields[1] > 8 then layout.long_names = layout.long_names + 1 end
      end
    end
  end
  return layout
end

local function ground(s, size)
  return s:add(ashlar.box{ size = size, center = { 0, 0, -0.1 } }, { support = true, name = "ground" })
end

local structures = {
  {
    name = "a block on the ground",
    stable = true,
    build = function()
      local s = ashlar.structure()
      ground(s, { 3, 3, 0.2 })
      s:add(ashlar.box{ size = { 1, 0.8, 0.5 }, center = { 0, 0, 0.25 } })
      return s
    end,
  },
  {
    name = "an overhanging stack",
    stable = false,
    build = function()
      local s = ashlar.structure()
      ground(s, { 6, 2, 0.2 })
      for i = 1, 4 do
        s:add(ashlar.box{ size = { 1, 1, 0.4 }, center = { 0.4 * (i - 1), 0, 0.2 + 0.4 * (i - 1) } })
      end
      return s
    end,
  },
  {
    name = "a running-bond wall, 8 friction sides",
    stable = true,
    options = { friction = 0.7, friction_sides = 8 },
    build = function()
      return models.wall{ length = 0.96, height = 0.28 }
    end,
  },
  {
    name = "a running-bond wall, box friction",
    stable = true,
    options = { friction = 0.7, friction_model = "box" },
    build = function()
      return models.wall{ length = 0.96, height = 0.28 }
    end,
  },
  {
    name = "a column pushed over by a point load",
    stable = false,
    build = function()
      local s = ashlar.structure()
      ground(s, { 3, 3, 0.2 })
      s:add(ashlar.box{ size = { 0.4, 0.4, 1 }, center = { 0, 0, 0.5 } })
      local top = s:add(ashlar.box{ size = { 0.4, 0.4, 1 }, center = { 0, 0, 1.5 } })
      s:add_load{ block = top, force = { 2000, 0, 0 }, at = { 0, 0, 2 } }
      return s
    end,
  },
  -- Friction-dominated and near-frictionless-limit problems, where the
  -- interior point used to stall (issue 26): t / R = 0.1 and 0.06 are
  -- below the arch's minimum thickness, so tension or sliding governs.
  {
    name = "an arch that slides at friction 0.2",
    stable = false,
    -- cvxopt stops with status "unknown" at 1e-10 here (its optimum then
    -- agrees to 5e-10); at 1e-8 it reports optimal.
    cvxopt_tolerance = 1e-8,
    -- Rounding bounds ashlar's error here at about 1e-13 (on an AMD EPYC
    -- it reaches 1.03e-13, then grows): 1e-12 is as tight as it is sure to
    -- converge everywhere.
    tolerance = 1e-12,
    options = { friction = 0.2 },
    build = function() return models.arch{ radius = 5, thickness = 0.5, voussoirs = 24 } end,
  },
  {
    name = "a thin arch at friction 1e4",
    stable = false,
    options = { friction = 1e4 },
    build = function() return models.arch{ radius = 5, thickness = 0.3, voussoirs = 24 } end,
  },
  {
    name = "a column holding a small point load",
    stable = true,
    options = { friction = math.huge },
    build = function()
      local s = ashlar.structure()
      ground(s, { 3, 3, 0.2 })
      local column = s:add(ashlar.box{ size = { 0.4, 0.4, 1 }, center = { 0, 0, 0.5 } })
      s:add_load{ block = column, force = { 300, -200, -1000 }, at = { 0.1, 0, 1 } }
      return s
    end,
  },
}

describe("ashlar.export_qp", function()
  local folder

  before_each(function() folder = support.temp_folder() end)
  after_each(function() support.remove_folder(folder) end)

  for _, case in ipairs(structures) do
    describe(case.name, function()
      local s, r, path

      before_each(function()
        s = case.build()
        -- The default tolerance bounds the mean complementarity, not the
        -- objective: a stable structure's objective (the force_weight
        -- regularisation alone) comes out only to about 1e-4 relative.
        local options = { tolerance = case.tolerance or 1e-13 }
        for key, value in pairs(case.options or {}) do options[key] = value end
        r = ashlar.analyze(s, options)
        path = folder .. "/problem.qps"
        ashlar.export_qp(s, path, case.options)
      end)

      it("is analysed as expected", function()
        assert.equal("converged", r.status)
        assert.equal(case.stable, r.stable)
      end)

      it("has the layout the problem implies", function()
        local layout = qps_layout(read_file(path))
        assert.same({ "NAME", "ROWS", "COLUMNS", "RHS", "BOUNDS", "QUADOBJ", "ENDATA" }, layout.sections)
        local free_blocks = 0
        for i = 1, #s do
          if not s:is_support(i) then free_blocks = free_blocks + 1 end
        end
        local vertices = #r.vertices
        local options = case.options or {}
        local friction_rows = options.friction == math.huge and 0 or
          options.friction_model == "box" and 4 or options.friction_sides or 4
        assert.equal(1, layout.rows.N)
        -- Planar structures (the model walls) balance Fx, Fz and My only.
        assert.equal((s:is_planar() and 3 or 6) * free_blocks, layout.rows.E)
        assert.equal(friction_rows * vertices, layout.rows.G or 0)
        assert.equal(4 * vertices, layout.columns)
        assert.equal(2 * vertices, layout.entries.BOUNDS)  -- f_u, f_v free
        assert.equal(4 * vertices, layout.entries.QUADOBJ)  -- the diagonal
        assert.equal(0, layout.long_names)
      end)

      it("has the optimum of ashlar.analyze when solved by cvxopt", function()
        local status, objective = cvxopt_solution(path, case.cvxopt_tolerance)
        assert.equal("optimal", status)
        local difference = math.abs(objective - r.objective)
        assert(difference <= 1e-6 * math.abs(r.objective) + 1e-9,
          ("cvxopt %.17g, ashlar %.17g"):format(objective, r.objective))
      end)
    end)
  end

  it("names its rows after 1-based blocks and its columns after vertices", function()
    local s = structures[1].build()
    local path = folder .. "/named.qps"
    ashlar.export_qp(s, path)
    local text = read_file(path)
    assert.matches("\nNAME +named\n", "\n" .. text)
    for _, row in ipairs{ "B2F1", "B2F2", "B2F3", "B2M1", "B2M2", "B2M3", "V1R1", "V4R4" } do
      assert.matches("\n [EG]  " .. row .. "\n", text)
    end
    assert.matches("\n FR BND U4\n", text)
    assert.matches("\n    C1 C1 0.0001\n", text)
    assert.is_nil(text:find("B1F", 1, true))  -- the ground has no balance rows
  end)

  it("raises an error naming the path it cannot write", function()
    local path = folder .. "/missing/problem.qps"
    local ok, message = pcall(ashlar.export_qp, structures[1].build(), path)
    assert.is_false(ok)
    assert.matches(path, message, 1, true)
  end)
end)
