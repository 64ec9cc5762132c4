-- Tutorial 07: bringing in your own model (docs/guide/07_import.md).
-- usage: ashlar scripts/examples/07_import.lua [figure folder]
local ashlar = require "ashlar"
local models = require "ashlar.models"
local out = arg[1] or "docs/guide/figures"
os.execute("mkdir -p '" .. out .. "'")
local files = os.tmpname()                 -- the model files go to a folder of their own
os.remove(files)
os.execute("mkdir -p '" .. files .. "'")

-- A mesh file with one object per block: here an arch written as OBJ.
ashlar.export(models.arch{ radius = 2, thickness = 0.3, voussoirs = 12 }, files .. "/arch.obj")
local s = ashlar.import(files .. "/arch.obj", { support = "^support" })
local supports = 0
for i = 1, #s do if s:is_support(i) then supports = supports + 1 end end
print(string.format("%d blocks, %d supports, first block %q", #s, supports, s:name(1)))
local r = ashlar.analyze(s, { friction = 0.7 })
print("stable:", r.stable)
ashlar.draw(s, out .. "/07_imported_arch.svg", { result = r, title = "imported from OBJ" })

-- The same with its forces, as a COMPAS Assembly, and back.
ashlar.export(s, files .. "/arch_compas.json", { format = "compas", result = r })
local c = ashlar.import(files .. "/arch_compas.json")
print(string.format("COMPAS round trip: %d blocks, %d interfaces, stable %s",
                    #c, #c:interfaces(), tostring(ashlar.analyze(c, { friction = 0.7 }).stable)))

-- A model with a 3 mm gap under its top block.
local gap = ashlar.structure()
gap:add(ashlar.box{ size = { 2, 1, 0.2 }, center = { 0, 0, -0.1 } }, { support = true, name = "ground" })
gap:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0, 0, 0.25 } }, { name = "bottom" })
gap:add(ashlar.box{ size = { 1, 1, 0.5 }, center = { 0.1, 0, 0.753 } }, { name = "top" })
ashlar.export(gap, files .. "/gap.obj")
local g = ashlar.import(files .. "/gap.obj", { support = "^ground" })
local floating = ashlar.analyze(g)
print(string.format("as modelled: stable %s, floating block %d", tostring(floating.stable), floating.floating[1]))
local nearest = g:contact_report{ tolerance = 0.001 }.gaps[1]
print(string.format("nearest gap: blocks %d and %d, %.4f m", nearest.a, nearest.b, nearest.gap))
print("with contact_tolerance = 0.005: stable", ashlar.analyze(g, { contact_tolerance = 0.005 }).stable)

-- Bad geometry is refused with a message that says what is wrong.
local ok, message = pcall(ashlar.block, { vertices = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
                                          faces = { { 1, 2, 3 }, { 1, 2, 4 }, { 1, 3, 4 }, { 2, 3, 4 } } })
print(message)

assert(#s == 14 and supports == 2 and r.stable, "the imported arch")
assert(#c == 14 and #c:interfaces() == #s:interfaces(), "the COMPAS round trip")
assert(not floating.stable and floating.floating[1] == 3, "the top block floats")
assert(math.abs(nearest.gap - 0.003) < 1e-5, "a 3 mm gap")
assert(not ok and message:find("inconsistent face orientation", 1, true), "an inverted face is refused")
os.execute("rm -r '" .. files .. "'")
