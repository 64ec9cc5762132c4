-- Tutorial 10: shaking: a rocking block under pulses of ground
-- acceleration, from a function and from a recorded file, and what a run
-- reports (docs/guide/10_dynamics.md).
-- usage: ashlar scripts/examples/10_dynamics.lua [figure folder]
local ashlar = require "ashlar"
package.path = "scripts/?.lua;" .. package.path
local rocking = require "rocking_pulse"   -- Zhang & Makris' closed form
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")

-- A slender block, 0.1 m wide and 1 m tall, standing free on a slab.
local block = rocking.block(0.1, 1.0)
print(string.format("alpha %.4f rad, p %.3f rad/s, uplift at %.3f m/s^2 (g tan alpha)",
                    block.alpha, block.p, block.threshold))

-- One-sine pulses a_p sin(w_p t) at w_p = 4 p: the closed form's least
-- amplitude that overturns it, and the simulation just below and above.
local w = 4 * block.p
local least = rocking.transitions(block, w, block.threshold, 5 * block.threshold, 100)[1].amplitude
print(string.format("closed form: overturns from a_p = %.3f m/s^2 (%.3f g tan alpha)", least, least / block.threshold))
for _, factor in ipairs{ 0.95, 1.05 } do
  local collapsed, peak = rocking.simulate(0.1, 1.0, 0.2, factor * least, w)
  print(string.format("a_p = %.2f x that: collapsed %s, peak displacement %.3f m", factor, tostring(collapsed), peak))
  assert(collapsed == (factor > 1), "the simulation overturns on the closed form's side")
end

-- The same pulse at 1.05 x, as a recorded accelerogram in the PEER AT2
-- format (accelerations in g, one sample a millisecond), read back.
local ap, dt = 1.05 * least, 1e-3
local samples = math.floor(2 * math.pi / w / dt) + 1
local lines = { "SYNTHETIC ONE-SINE PULSE", "tutorial 10", "ACCELERATION TIME SERIES IN UNITS OF G",
                string.format("NPTS=%6d, DT=%8.4f SEC", samples, dt) }
for k = 0, samples - 1 do lines[#lines + 1] = string.format("%.9e", ap * math.sin(w * k * dt) / 9.81) end
local record = os.tmpname() .. ".at2"
local f = assert(io.open(record, "w"))
f:write(table.concat(lines, "\n"), "\n")
f:close()
local pulse = ashlar.ground_motion{ path = record }
os.remove(record)
print(string.format("record: %d samples over %.3f s, peak %.3f m/s^2 at %.3f s",
                    pulse.samples, pulse.duration, pulse.peak, pulse.peak_time))

local s = ashlar.structure()
s:add(ashlar.box{ size = { 3, 0.4, 0.1 }, center = { 0, 0, -0.05 } }, { support = true, name = "slab" })
s:add(ashlar.box{ size = { 0.1, 0.2, 1.0 }, center = { 0, 0, 0.5 } }, { name = "block" })
local sim = ashlar.simulate(s, { duration = 2.5, friction = 0.8, record_every = 1, ground_acceleration = pulse })
local summary = sim:summary()
print(string.format("first movement %.3f s, collapse at %.3f s, peak displacement %.3f m, fallen: %s",
                    summary.first_movement, summary.collapse_time, summary.peak_displacement,
                    s:name(summary.fallen[1])))
-- Housner: it lifts off when the pulse first reaches g tan alpha; it has
-- "moved" once a vertex has gone 1e-3 of its size (moved_fraction), later.
local uplift = math.asin(block.threshold / ap) / w
print(string.format("Housner's uplift at %.3f s", uplift))
assert(summary.collapsed and summary.first_movement > uplift and summary.collapse_time > pulse.duration)
local chart = sim:chart{ path = out .. "/10_rocking_displacement.png", title = "Slender block, one-sine pulse 1.05 x the least that overturns it" }
print("chart: " .. #chart.series .. " series")
