-- The kinematic method on a built vault (the Armadillo, tests/data/compas_cra)
-- and on the defects it showed there: a round that is not least constraint
-- gives a block held by a steep face no force from that face, and strengths
-- that follow only the last round's compressions are lost by a block that
-- rocks from vertex to vertex of its joints.
local ashlar = require "ashlar"

local cases = dofile("../../scripts/kinematic_cases.lua")

describe("the kinematic method on steep faces and a built vault", function()
  it("presses a block onto a steep incline in its first round (tan theta <= mu, it stands at once)", function()
    -- 1 x 1 x 0.5 m block on a slab tilted 61.43 degrees, mu = 2 (atan 2 =
    -- 63.43 degrees; it would tip at atan 2 too, the same angle): it stands.
    -- The face's normal is 61 degrees from vertical; with the dead zone of a
    -- linear virtual-load cost the first round gave it no compression and
    -- the strength grew back over 38 rounds; by least constraint the weight
    -- presses it in at once.
    local theta = math.atan(2) - math.rad(2)
    local r = ashlar.analyze(cases.incline(theta), { friction = 2, method = "kinematic" })
    assert.is_true(r.stable)
    assert.is_true(r.rounds <= 5, "rounds " .. r.rounds)
    -- and past it, it slides: not held by a squeeze nothing makes.
    local falls = ashlar.analyze(cases.incline(math.atan(0.6) + math.rad(2)), { friction = 0.6, method = "kinematic" })
    assert.is_false(falls.stable)
  end)

  it("lets the Armadillo vault stand at mu 0.84, as the dynamics from rest does", function()
    -- 399 voussoirs (33 supports), warped faces. Voussoir C-11-1 (block 304,
    -- a quarter of the mean weight) sits in a slot whose faces (to its
    -- neighbours 311 and 363) diverge by 6.8 degrees towards the free edge:
    -- its own weight presses it against 311's face (normal 85 degrees from
    -- vertical), and the course's thrust squeezes it, which also pushes it
    -- out, so friction must hold it as the squeeze grows. ashlar.simulate
    -- from rest (mu 0.84, 0.2 s) moves no vertex of the vault more than
    -- 2e-6 m; the equilibrium method and an independent LP find it standing.
    -- With strengths from the last round alone, C-11-1 rocked onto a vertex
    -- without strength every round, its joints lost their strength, the
    -- thrust went round it and it fell alone (infeasibility 6.6e-4); the
    -- rounds now build strengths up before the plain rounds.
    local s = ashlar.import("../data/compas_cra/armadillo_cra.json", { planarity = 0.05, interfaces = "detect" })
    local r = ashlar.analyze(s, { friction = 0.84, contact_tolerance = 0.03, method = "kinematic" })
    assert.equal("converged", r.status)
    assert.is_true(r.stable, tostring(r))
    assert.equal(0, r.infeasibility)
    assert.is_true(r.rounds <= 40, "rounds " .. r.rounds)
    -- The thrust passes through C-11-1: each side squeezes it with several
    -- times its weight (about 1,100 and 1,300 N on 152 N).
    local weight = 9.81 * s:block(304):mass()
    local squeezed = {}
    for _, joint in ipairs(r.interfaces) do
      if joint.a == 304 or joint.b == 304 then
        local other = joint.a == 304 and joint.b or joint.a
        squeezed[other] = joint.normal_force
      end
    end
    assert.is_true(squeezed[311] > 3 * weight, tostring(squeezed[311]))
    assert.is_true(squeezed[363] > 3 * weight, tostring(squeezed[363]))
  end)
end)
