-- The coupled rigid-block analysis (method = "cra") on a built vault: the
-- Armadillo (Block Research Group, 2016; tests/data/compas_cra, from
-- compas_cra's samples), 399 voussoirs, 33 supports, on the contacts ashlar
-- detects. The exact program (complementarity = 0) makes no progress on it
-- (see docs/api.md); with the complementarity relaxed to kappa = 0.1 IPOPT
-- converges. Slow: 66 s in a Release build on 2 cores (231
-- IPOPT iterations; the equilibrium method takes 0.23 s), so it has a spec
-- file of its own and a COST in tests/CMakeLists.txt that starts it first.
local ashlar = require "ashlar"
local support = require "spec_support"

local PATH = "../data/compas_cra/armadillo_cra.json"  -- specs run in tests/lua
local G = 9.81

describe("method = 'cra' on the Armadillo vault", function()
  it("converges with complementarity 0.1: stable, the supports carry the weight", function()
    local s = ashlar.import(PATH, { planarity = 0.05, interfaces = "detect" })
    local r = ashlar.analyze(s, { method = "cra", friction = 0.84, contact_tolerance = 0.03,
                                  complementarity = 0.1 })
    assert.is_true(r.status == "converged" or r.status == "inaccurate", r.status)
    assert.is_true(r.stable)
    assert.equal(0, r.infeasibility)
    -- The reactions: every interface between a support and a free block,
    -- as the force on the free block, sums to the weight of the free blocks.
    local weight = 0
    for i = 1, #s do
      if not s:is_support(i) then weight = weight + s:block(i):mass() * G end
    end
    local sum = { 0, 0, 0 }
    local reactions = 0
    for _, f in ipairs(r.interfaces) do
      local sa, sb = s:is_support(f.a), s:is_support(f.b)
      local sign = (sa and not sb) and 1 or (sb and not sa) and -1 or 0
      if sign ~= 0 then
        reactions = reactions + 1
        for k = 1, 3 do sum[k] = sum[k] + sign * f.resultant[k] end
      end
    end
    assert.is_true(reactions > 33)
    support.near(sum[3], weight, 1e-6 * weight, "vertical reactions")
    support.near(sum[1], 0, 1e-6 * weight, "horizontal reactions x")
    support.near(sum[2], 0, 1e-6 * weight, "horizontal reactions y")
  end)
end)
