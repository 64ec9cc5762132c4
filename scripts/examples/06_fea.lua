-- Tutorial 06: elastic FEA with contact, and how it compares with
-- equilibrium (docs/guide/06_fea.md).
-- usage: ashlar scripts/examples/06_fea.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

local function arch(t) return models.arch{ radius = 5, thickness = t, voussoirs = 24 } end

-- t/R = 0.12: equilibrium stands; the FEA with every contact tied pulls.
local s = arch(0.6)
local tied = ashlar.fea(s, { relax = false })
print(string.format("tied:        %s, %d nodes in tension, %.0f N", tied.status,
                    tied.history[1].tensile, tied.history[1].tension))
local fe = ashlar.fea(s)                                        -- unilateral contact, the default
print(string.format("unilateral:  %s after %d iterations", fe.status, fe.iterations))
local relaxed = ashlar.fea(s, { method = "relaxation", release = "largest" })
print(string.format("relaxation:  %s after %d iterations", relaxed.status, relaxed.iterations))
print("equilibrium: stable", ashlar.analyze(s, { friction = math.huge }).stable)

-- Across thickness: equilibrium and unilateral FEA give the same verdict.
local rows = {}
for k = 0, 8 do
  local t = 0.40 + 0.05 * k
  local a = arch(t)
  local eq = ashlar.analyze(a, { friction = math.huge }).stable
  local f = ashlar.fea(a)
  local t0 = ashlar.fea(a, { relax = false }).history[1].tensile
  rows[#rows + 1] = { t = t / 5, tensile = t0, agree = (f.status == "compression_only") == eq }
  print(string.format("t/R %.2f  equilibrium %-8s FEA %-16s tied nodes in tension %d",
                      t / 5, eq and "stable" or "unstable", f.status, t0))
  assert(rows[#rows].agree, "FEA and equilibrium agree at t/R " .. t / 5)
end
ashlar.chart{ path = out .. "/06_tied_tension.svg", data = rows, x = "t", y = "tensile",
              title = "Arch, 24 voussoirs: contact nodes in tension, every contact tied",
              x_label = "t / R", y_label = "nodes in tension" }

assert(rows[7].tensile == 2 and rows[8].tensile == 0, "no tied node in tension from t/R 0.15")
assert(tied.status == "tension" and tied.history[1].tensile == 10, "tied: 10 nodes in tension")
assert(math.abs(tied.history[1].tension - 9258.8) < 1, "tied: 9.26 kN of tension")
assert(fe.status == "compression_only" and fe.iterations == 2, "unilateral: compression only")
assert(relaxed.status == "compression_only" and relaxed.iterations == 2, "relaxation: compression only after 2")
