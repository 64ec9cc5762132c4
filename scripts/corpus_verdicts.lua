-- The real assemblies of the test corpus (tests/data/compas_cra: compas_cra's
-- samples and the Armadillo vault) through every method: blocks, the
-- file's interfaces and those detected, each method's verdict and time, and
-- the arbiter's (ashlar.compare_methods) with what decided it.
--
--   build/bin/ashlar scripts/corpus_verdicts.lua [friction (0.84)] [cra on the Armadillo: yes|no (no)]
-- CRA on the Armadillo (about 2 minutes) runs with complementarity 0.1, the
-- exact program does not converge there; the arbiter runs CRA on the small
-- samples only.
local ashlar = require "ashlar"

local folder = "tests/data/compas_cra/"
local friction = tonumber(arg and arg[1]) or 0.84
local cra_on_vault = (arg and arg[2]) == "yes"

-- The supports compas_cra's examples fix: node 0 for the cubes, nodes 0
-- and 1 for the others; the Armadillo marks its own (is_support).
local files = {
  { "cubes.json", { "node 0" } }, { "type-a.json", { "node 0", "node 1" } },
  { "type-b.json", { "node 0", "node 1" } }, { "type-c.json", { "node 0", "node 1" } },
  { "type-d.json", { "node 0", "node 1" } }, { "H.json", { "node 0", "node 1" } },
  { "A.json", { "node 0", "node 1" } }, { "armadillo_cra.json" },
}

local function load(file, supports, interfaces)
  local options = { interfaces = interfaces }
  if supports then
    local set = {}
    for _, name in ipairs(supports) do set[name] = true end
    options.support = function(name) return set[name] == true end
  else
    options.planarity = 0.05
  end
  return ashlar.import(folder .. file, options)
end

local function timed(f, ...)
  local t = ashlar.clock()
  local ok, value = pcall(f, ...)
  return ok, value, ashlar.clock() - t
end

local function words(r)
  if r.stable then return "stands" end
  return (r.status == "converged" or r.status == "infeasible") and "falls" or r.status
end

print(("friction %.2f; contact tolerance: 3 cm on the Armadillo, the default elsewhere"):format(friction))
print(("%-18s %6s %6s %8s | %-16s %-16s %-16s | %-8s %-9s %s"):format("file", "blocks", "file's", "detected",
  "equilibrium", "kinematic", "cra", "verdict", "by", "arbiter s"))
for _, entry in ipairs(files) do
  local file, supports = entry[1], entry[2]
  local stored = load(file, supports)
  local s = load(file, supports, "detect")
  local vault = supports == nil
  local options = { friction = friction, contact_tolerance = vault and 0.03 or nil }
  local cells = {}
  for _, method in ipairs{ "equilibrium", "kinematic", "cra" } do
    if method == "cra" and vault and not cra_on_vault then
      cells[#cells + 1] = "(not run)"
    else
      local o = {}
      for k, v in pairs(options) do o[k] = v end
      o.method = method
      if method == "cra" and vault then o.complementarity = 0.1 end
      local ok, r, seconds = timed(ashlar.analyze, s, o)
      cells[#cells + 1] = ok and ("%s %.2fs"):format(words(r), seconds) or "error"
    end
  end
  local o = { cra = not vault, margin = false }
  for k, v in pairs(options) do o[k] = v end
  local ok, c, seconds = timed(ashlar.compare_methods, s, o)
  print(("%-18s %6d %6d %8d | %-16s %-16s %-16s | %-8s %-9s %.2f"):format(file, #s, #stored:interfaces(),
    #s:interfaces{ tolerance = options.contact_tolerance }, cells[1], cells[2], cells[3],
    ok and c.verdict or "error", ok and (c.decided_by or "-") or "", seconds))
end
