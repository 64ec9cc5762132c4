-- The public Lua API's names against docs/api.md, both ways; run in the host:
--   ashlar tests/tools/api_names.lua docs/api.md bindings
-- Live: every function of the `ashlar` table, of `require "ashlar.models"`,
-- and every method of the userdata types (the registry's "ashlar.*"
-- metatables: Structure, Block, Result, FeaResult, Simulation, Study;
-- the methods of those whose __index is a function are found by asking a
-- small instance for every string literal in the bindings' sources).
-- Documented: every `ashlar.name`, `models.name` and `x:name(` / `x:name{`
-- in the file. Each live name must be documented (a method as `x:name(`,
-- whatever the receiver is called), and each documented call `ashlar.name(`,
-- `models.name{` or `x:name(` must exist. Prints the mismatches; an error
-- (exit 1) when there are any.
local path = assert(arg[1], "usage: ashlar api_names.lua docs/api.md bindings")
local bindings = assert(arg[2], "usage: ashlar api_names.lua docs/api.md bindings")
local f = assert(io.open(path, "r"))
local text = f:read("a")
f:close()
local models = require "ashlar.models"

local function sorted_keys(t)
  local list = {}
  for k in pairs(t) do list[#list + 1] = k end
  table.sort(list)
  return list
end

-- What the file documents.
local doc_ashlar, doc_models, doc_methods = {}, {}, {}
local doc_ashlar_calls, doc_models_calls = {}, {}
for name, after in text:gmatch("ashlar%.([%a_][%w_]*)(.?)") do
  doc_ashlar[name] = true
  if after == "(" or after == "{" then doc_ashlar_calls[name] = true end
end
for name, after in text:gmatch("%f[%w_.]models%.([%a_][%w_]*)(.?)") do
  doc_models[name] = true
  if after == "(" or after == "{" then doc_models_calls[name] = true end
end
for receiver, name in text:gmatch("%f[%w_]([%a_][%w_]*):([%a_][%w_]*)[%({]") do
  doc_methods[name] = doc_methods[name] or receiver
end

-- What exists. Types whose __index is a function (Result, FeaResult,
-- Simulation compute their fields on access) are asked, on a small
-- instance, for every string literal of the bindings' sources.
local instances = {}
do
  local s = ashlar.structure()
  s:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true })
  s:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.25 } })
  instances.Result = ashlar.analyze(s)
  instances.FeaResult = ashlar.fea(s)
  instances.Simulation = ashlar.simulate(s, { duration = 0.01 })
end
local candidates = {}
local pipe = assert(io.popen("cat '" .. bindings .. "'/*.cpp"))
for name in pipe:read("a"):gmatch('"([%a_][%w_]*)"') do candidates[name] = true end
pipe:close()

local live_methods, types = {}, {}
local function add_method(name, type_name)
  live_methods[name] = live_methods[name] or {}
  table.insert(live_methods[name], type_name)
end
for key, mt in pairs(debug.getregistry()) do
  if type(key) == "string" and key:match("^ashlar%.%u") and type(mt) == "table" then
    local type_name = key:gsub("^ashlar%.", "")
    if type(mt.__index) == "table" then
      types[#types + 1] = type_name
      for name, value in pairs(mt.__index) do
        if type(value) == "function" and not name:match("^__") then add_method(name, type_name) end
      end
    elseif instances[type_name] then
      types[#types + 1] = type_name
      for name in pairs(candidates) do
        local ok, value = pcall(function() return instances[type_name][name] end)
        if ok and type(value) == "function" then add_method(name, type_name) end
      end
    end
  end
end
table.sort(types)

local problems, checked = {}, { live = 0, documented = 0, functions = 0, models = 0, methods = 0 }
local function problem(fmt, ...) problems[#problems + 1] = string.format(fmt, ...) end

-- The functions of a module table (rawget: ashlar raises on unknown names).
local function check_module(module, prefix, documented, count)
  for _, name in ipairs(sorted_keys(module)) do
    if type(rawget(module, name)) == "function" then
      checked.live, checked[count] = checked.live + 1, checked[count] + 1
      if not documented[name] then problem("%s.%s exists but docs/api.md does not mention it", prefix, name) end
    end
  end
end
check_module(ashlar, "ashlar", doc_ashlar, "functions")
check_module(models, "models", doc_models, "models")
for _, name in ipairs(sorted_keys(live_methods)) do
  checked.live, checked.methods = checked.live + 1, checked.methods + 1
  if not doc_methods[name] then
    table.sort(live_methods[name])
    problem("method %s:%s exists but docs/api.md never calls it as x:%s(...)",
            table.concat(live_methods[name], "/"), name, name)
  end
end

for _, name in ipairs(sorted_keys(doc_ashlar_calls)) do
  checked.documented = checked.documented + 1
  if type(rawget(ashlar, name)) ~= "function" then problem("docs/api.md calls ashlar.%s, which does not exist", name) end
end
for _, name in ipairs(sorted_keys(doc_models_calls)) do
  checked.documented = checked.documented + 1
  if type(rawget(models, name)) ~= "function" then problem("docs/api.md calls models.%s, which does not exist", name) end
end
for _, name in ipairs(sorted_keys(doc_methods)) do
  checked.documented = checked.documented + 1
  if not live_methods[name] then
    problem("docs/api.md calls %s:%s, which is no method of %s", doc_methods[name], name, table.concat(types, ", "))
  end
end

print(string.format("%d live names checked against docs/api.md (%d ashlar functions, %d models, %d method names of %s), "
                    .. "%d documented calls checked against the live API",
                    checked.live, checked.functions, checked.models, checked.methods, table.concat(types, ", "),
                    checked.documented))
for _, p in ipairs(problems) do print("FAIL " .. p) end
if #problems > 0 then error(#problems .. " mismatch(es) between the live API and docs/api.md", 0) end
