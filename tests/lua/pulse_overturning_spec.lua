-- A collapse map over the amplitude and the frequency of a one-sine pulse of
-- ground acceleration (ashlar.study over the grid, st:chart{ kind = "map" }),
-- checked against the closed form of Zhang and Makris (2001), "Rocking
-- response of free-standing blocks under cycloidal pulses", J. Eng. Mech.
-- 127(5): the linearised rocking of a slender block, solved piecewise in
-- closed form between impacts (Housner's restitution), gives for each pulse
-- whether the block overturns (scripts/rocking_pulse.lua), and Housner's
-- (1963) uplift threshold a_g = g tan(alpha) below which it never moves.
--
-- The block: 0.1 m wide, 1 m tall, 0.2 m deep (alpha = 0.0997 rad, p = 3.83
-- rad/s). Tolerance: the simulated verdict agrees with the closed form's at
-- every grid point whose amplitude is more than 5 % from an amplitude where
-- the closed form's verdict changes (the linearisation of sin and cos at
-- alpha = 0.1 rad and the time step move the boundary by about 1 %: on the
-- figure's 14 x 27 grid every simulated bracket of the minimum overturning
-- amplitude holds the closed form's, but at w_p / p = 6, 0.8 % off).
local ashlar = require "ashlar"
package.path = "../../scripts/?.lua;" .. package.path
local rocking = require "rocking_pulse"

local width, height, depth = 0.1, 1.0, 0.2
local block = rocking.block(width, height)
local tolerance = 0.05

describe("a collapse map of a rocking block under one-sine pulses", function()
  it("matches Zhang and Makris' closed-form overturning over a grid of pulses", function()
    local ratios, amplitudes = { 2, 3, 4, 5, 6, 7 }, { 0.9, 1.15, 1.5, 2, 2.6, 3.4, 4.5 }
    local study = ashlar.study{
      name = "pulse", workers = 1, progress = false,
      params = { ratio = ratios, amplitude = amplitudes },
      run = function(p)
        local collapsed, peak, moved = rocking.simulate(width, height, depth, p.amplitude * block.threshold,
                                                        p.ratio * block.p)
        return { collapsed = collapsed, peak = peak, moved = moved ~= nil }
      end,
    }
    -- The closed form's verdict changes, per frequency, up to 5 g tan(alpha).
    local changes = {}
    for _, ratio in ipairs(ratios) do
      changes[ratio] = rocking.transitions(block, ratio * block.p, block.threshold, 5 * block.threshold, 100)
    end
    local checked, banded = 0, 0
    for _, row in ipairs(study:rows()) do
      assert.equal("ok", row.run_status)
      local w, ap = row.ratio * block.p, row.amplitude * block.threshold
      if row.amplitude < 1 then
        -- Below Housner's uplift threshold nothing moves.
        assert.is_false(row.moved, "moved below the uplift threshold")
        assert.is_false(row.collapsed)
      end
      local near = false
      for _, change in ipairs(changes[row.ratio]) do
        if math.abs(change.amplitude - ap) <= tolerance * change.amplitude then near = true end
      end
      if near then
        banded = banded + 1
      else
        checked = checked + 1
        local expected = rocking.overturns(block, ap, w)
        assert.equal(expected, row.collapsed,
          ("w_p / p = %g, a_p / (g tan alpha) = %g: closed form %s, simulated %s"):format(
            row.ratio, row.amplitude, tostring(expected), tostring(row.collapsed)))
      end
    end
    assert.is_true(checked >= 36, ("only %d of %d grid points outside the band"):format(checked, checked + banded))
    -- The map: the boundary between the verdicts, the closed form over it.
    local curve = {}
    for _, ratio in ipairs(ratios) do
      if changes[ratio][1] then curve[#curve + 1] = { ratio, changes[ratio][1].amplitude / block.threshold } end
    end
    local path = os.tmpname() .. ".png"
    local map = study:chart{ path = path, x = "ratio", y = "amplitude", z = "collapsed", kind = "map",
                             curves = { curve } }
    assert.is_true(#map.boundary >= 1)
    assert.equal(#ratios * #amplitudes, map.cells)
    os.remove(path)
    local support = require "spec_support"
    support.expect_error({ "curves[1][2]: expected {x, y}, got number" }, function()
      study:chart{ path = path, x = "ratio", y = "amplitude", z = "collapsed", kind = "map", curves = { { { 1, 2 }, 3 } } }
    end)
    support.expect_error({ "chart: map: curve 1 must have at least 2 points" }, function()
      study:chart{ path = path, x = "ratio", y = "amplitude", z = "collapsed", kind = "map", curves = { { { 1, 2 } } } }
    end)
    support.expect_error({ "curves: taken by kind = \"map\" only" }, function()
      study:chart{ path = path, x = "ratio", y = "amplitude", curves = { { { 1, 2 }, { 2, 3 } } } }
    end)
  end)
end)
