-- Helpers shared by the busted specs (found on package.path through the
-- specs' working folder, tests/lua).
local support = {}

-- Quotes a string for the shell.
function support.quote(text)
  return "'" .. text:gsub("'", [['\'']]) .. "'"
end

function support.near(actual, expected, tolerance, what)
  assert(math.abs(actual - expected) <= tolerance,
    ("%sexpected %.17g, got %.17g (tolerance %g)"):format(what and what .. ": " or "", expected,
      actual, tolerance))
end

-- Calls f with the arguments from a Lua function, so that the error has a
-- Lua caller to blame, and checks that its message starts with a Lua
-- file:line (this file's, or the spec's when f is a closure there) and holds
-- every fragment (plain text).
function support.expect_error(fragments, f, ...)
  local args = table.pack(...)
  -- Not a tail call: the wrapper must stay on the stack as the caller.
  local ok, message = pcall(function() f(table.unpack(args, 1, args.n)) end)
  assert(not ok, "expected an error")
  message = tostring(message)
  assert(message:match("^[^:]+%.lua:%d+: "), "no file:line in: " .. message)
  for _, fragment in ipairs(fragments) do
    assert(message:find(fragment, 1, true), ("'%s' not in: %s"):format(fragment, message))
  end
  return message
end

-- As expect_error, and the error blames the generator's caller (the
-- wrapper in this file), not a line inside the model library.
function support.expect_generator_error(fragments, f, ...)
  local message = support.expect_error(fragments, f, ...)
  assert(message:match("^[^:]*spec_support%.lua:%d+: "), "blames the wrong line: " .. message)
  return message
end

-- The smallest value at which stands(value) holds, by bisection between a
-- value that fails and one that stands, to an absolute tolerance.
function support.threshold(stands, failing, standing, tolerance)
  assert(not stands(failing) and stands(standing), "the bracket does not hold the threshold")
  while standing - failing > tolerance do
    local middle = (failing + standing) / 2
    if stands(middle) then standing = middle else failing = middle end
  end
  return (failing + standing) / 2
end

-- Checks that the threshold of stands (as in support.threshold) lies within
-- `relative` of `reference`: it fails just below the band and stands just
-- above it, two calls instead of a bisection (stability only grows with the
-- value). On failure it bisects from [failing, standing] to report the value.
function support.threshold_within(stands, reference, relative, what, failing, standing)
  if not stands((1 - relative) * reference) and stands((1 + relative) * reference) then return end
  local value = support.threshold(stands, failing, standing, 1e-4 * reference)
  error(("%s: threshold %.6g is %+.2f%% from %.6g (allowed %g%%)"):format(what, value,
    100 * (value - reference) / reference, reference, 100 * relative), 2)
end

-- Total volume of a structure's free blocks (supports left out).
-- Asserts that s's interfaces are exactly `contacts`, a list of
-- { name_a, name_b, area } (either order), each area to 1e-12.
function support.expect_contacts(s, contacts)
  local expected, count = {}, 0
  for _, c in ipairs(contacts) do
    local i, j = s:find(c[1]), s:find(c[2])
    assert(i and j, "no block " .. (i and c[2] or c[1]))
    expected[math.min(i, j) .. "-" .. math.max(i, j)] = c[3]
    count = count + 1
  end
  local interfaces = s:interfaces()
  assert(count == #interfaces, ("expected %d contacts, got %d"):format(count, #interfaces))
  for _, f in ipairs(interfaces) do
    local key = math.min(f.a, f.b) .. "-" .. math.max(f.a, f.b)
    assert(expected[key], "spurious contact " .. s:name(f.a) .. " / " .. s:name(f.b))
    support.near(f.area, expected[key], 1e-12, s:name(f.a) .. " / " .. s:name(f.b))
    expected[key] = nil  -- a second interface between the pair is spurious
  end
end

-- The keys of t, sorted.
function support.sorted_keys(t)
  local keys = {}
  for key in pairs(t) do keys[#keys + 1] = key end
  table.sort(keys)
  return keys
end

-- The sum of a Block method's value ("volume", "mass") over the free blocks.
function support.free_total(s, quantity)
  local total = 0
  for i = 1, #s do
    if not s:is_support(i) then
      local block = s:block(i)
      total = total + block[quantity](block)
    end
  end
  return total
end

function support.free_volume(s) return support.free_total(s, "volume") end

-- A new empty folder under /tmp, and its removal.
function support.temp_folder()
  local path = os.tmpname()
  os.remove(path)
  assert(os.execute("mkdir " .. support.quote(path)))
  return path
end

-- Runs shell commands with stdout and stderr together; returns the output
-- and the exit code of the last command.
function support.run(commands)
  local pipe = assert(io.popen("{ " .. commands .. "\n} 2>&1", "r"))
  local output = pipe:read("a")
  local _, _, code = pipe:close()
  return output, code
end

-- The absolute folder of the file of the function at `level` (1: the caller),
-- for paths that must survive a `cd`.
function support.script_folder(level)
  local source = debug.getinfo(level + 1, "S").source:match("^@(.*)$") or "."
  local folder = source:match("^(.*)/[^/]*$") or "."
  if folder:sub(1, 1) ~= "/" then folder = assert(os.getenv("PWD"), "no PWD") .. "/" .. folder end
  return folder
end

function support.remove_folder(path)
  os.execute("rm -rf " .. support.quote(path))
end

function support.read_file(path)
  local file = assert(io.open(path, "rb"))
  local text = file:read("a")
  file:close()
  return text
end

function support.write_file(path, text)
  local file = assert(io.open(path, "w"))
  assert(file:write(text))
  assert(file:close())
end

-- Adds to every free block of s a point load of `factor` times its weight
-- along +x at its centroid: a lateral body force, for checking load factors
-- and tilts with ashlar.analyze. Returns s.
function support.push_laterally(s, factor)
  for i = 1, #s do
    if not s:is_support(i) then
      local b = s:block(i)
      s:add_load{ block = i, force = { factor * b:mass() * 9.81, 0, 0 }, at = b:centroid() }
    end
  end
  return s
end

-- Largest force and moment imbalance of the free blocks (N, N m) under their
-- weights and the result's vertex forces (statics alone, no point loads),
-- and the largest vertex tension (N). `contact`: the options of
-- s:interfaces that match the analysis' contact options (default none).
function support.statics(s, r, contact)
  local force, moment = {}, {}
  for i = 1, #s do
    if not s:is_support(i) then
      local b = s:block(i)
      force[i] = { 0, 0, -9.81 * b:mass() }
      moment[i] = { 0, 0, 0 }
    end
  end
  local function add(i, f, at, sign)
    if not force[i] then return end
    local c = s:block(i):centroid()
    local arm = { at[1] - c[1], at[2] - c[2], at[3] - c[3] }
    for k = 1, 3 do force[i][k] = force[i][k] + sign * f[k] end
    local m = { arm[2] * f[3] - arm[3] * f[2], arm[3] * f[1] - arm[1] * f[3], arm[1] * f[2] - arm[2] * f[1] }
    for k = 1, 3 do moment[i][k] = moment[i][k] + sign * m[k] end
  end
  local tension = 0
  local contacts = s:interfaces(contact)
  for _, v in ipairs(r.vertices) do
    local f = r.interfaces[v.interface]
    local contact = contacts[v.interface]
    tension = math.max(tension, v.tension)
    local n, u, w = contact.normal, contact.u, contact.v
    local normal = v.compression - v.tension
    local vec = {}
    for k = 1, 3 do vec[k] = normal * n[k] + v.friction_u * u[k] + v.friction_v * w[k] end
    add(f.b, vec, v.position, 1)
    add(f.a, vec, v.position, -1)
  end
  local worst_force, worst_moment = 0, 0
  for i in pairs(force) do
    for k = 1, 3 do
      worst_force = math.max(worst_force, math.abs(force[i][k]))
      worst_moment = math.max(worst_moment, math.abs(moment[i][k]))
    end
  end
  return worst_force, worst_moment, tension
end

-- The verdict of an LP that shares no code with ashlar's analysis
-- (tests/tools/equilibrium_lp.py, cvxopt): does a compression-only
-- equilibrium within the four-sided friction pyramid exist on the contact
-- polygons s:interfaces(contact) finds? Returns its JSON's stable,
-- infeasibility and failing blocks (1-based). `friction`: mu, or
-- math.huge for no sliding.
-- Writes the input of tests/tools/equilibrium_lp.py for s (see
-- independent_verdict) to `path`.
function support.write_equilibrium_lp(s, friction, contact, path)
  local function point(p) return ("[%.17g,%.17g,%.17g]"):format(p[1], p[2], p[3]) end
  local parts = {}
  for i = 1, #s do
    local b = s:block(i)
    parts[#parts + 1] = ('{"support":%s,"weight":%.17g,"centroid":%s,"size":%.17g}'):format(
      tostring(s:is_support(i)), 9.81 * b:mass(), point(b:centroid()), b:volume() ^ (1 / 3))
  end
  local blocks = table.concat(parts, ",")
  parts = {}
  for _, f in ipairs(s:interfaces(contact)) do
    local vertices = {}
    for k, p in ipairs(f.vertices) do vertices[k] = point(p) end
    parts[#parts + 1] = ('{"a":%d,"b":%d,"normal":%s,"u":%s,"v":%s,"vertices":[%s]}'):format(
      f.a, f.b, point(f.normal), point(f.u), point(f.v), table.concat(vertices, ","))
  end
  support.write_file(path, ('{"friction":%s,"blocks":[%s],"interfaces":[%s]}'):format(
    friction == math.huge and "null" or ("%.17g"):format(friction), blocks, table.concat(parts, ",")))
end

function support.independent_verdict(s, friction, contact)
  local path = os.tmpname()
  support.write_equilibrium_lp(s, friction, contact, path)
  local here = debug.getinfo(1, "S").source:match("^@(.*)/[^/]*$") or "."
  local script = here .. "/../tools/equilibrium_lp.py"
  local output, code = support.run("/usr/bin/python3 " .. support.quote(script) .. " " .. support.quote(path))
  os.remove(path)
  assert(code == 0, "equilibrium_lp.py failed:\n" .. output)
  local stable = output:match('"stable": (%a+)')
  local infeasibility = tonumber(output:match('"infeasibility": ([^,}]+)'))
  assert(stable and infeasibility, "unexpected output of equilibrium_lp.py:\n" .. output)
  local failing = {}
  for block in (output:match('"failing_blocks": %[([^%]]*)%]') or ""):gmatch("%d+") do
    failing[#failing + 1] = tonumber(block)
  end
  return stable == "true", infeasibility, failing
end

-- The text of each <text> element of an SVG that PLplot's svg driver wrote
-- (every character as &#xHH;; a superscript in a <tspan> raised by dy < 0,
-- here written "^": "10^-6").
function support.svg_texts(svg)
  local texts = {}
  for body in svg:gmatch("<text.->(.-)</text>") do
    body = body:gsub('<tspan dy="%-[^>]*>', "^")
    local text = {}
    for piece in body:gmatch("[%^]?&#x%x+;") do
      local raised, code = piece:match("^(%^?)&#x(%x+);$")
      text[#text + 1] = raised .. utf8.char(tonumber(code, 16))
    end
    texts[#texts + 1] = table.concat(text)
  end
  return texts
end

-- Whether `list` holds `value`.
function support.contains(list, value)
  for _, item in ipairs(list) do
    if item == value then return true end
  end
  return false
end

return support
