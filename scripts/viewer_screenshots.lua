-- The README's pictures of the HTML viewer (ashlar.export to .html), taken
-- by headless chromium (Debian: chromium):
--   ashlar scripts/viewer_screenshots.lua [folder] [pages]
-- folder: the PNGs (default docs/figures/viewer); pages: where the .html
-- pages are written (default: a new temporary folder, printed). Pictures:
--   arch_forces     a semicircular arch, 15 voussoirs, planar (front view,
--                   orthographic), friction 0.7: its interfaces, one arrow
--                   per interface (its resultant, at its centre of
--                   pressure), the thrust line, the key and the force scale
--   dome_weights    a 12 x 8 dome coloured by ashlar.important_weights
--   dome_tension    the same dome 0.15 m thick (too thin to stand), coloured
--                   by the tension its best equilibrium needs, legend from 0
--   arcade_thrust   a two-span arcade (models.arch_bridge{ spans = 2,
--                   spandrel = false }): its thrust line branching at the pier
--   groin_vault_network  the groin vault (models.groin_vault{}), friction
--                   0.7: its thrust network, tubes as thick as their joints'
--                   forces, blocks translucent
-- and prints each page's size (the issue's budget: the arch with forces,
-- a 16 x 18 dome with forces and the groin vault, each written here).
-- Prints the time of each analysis and export.
local ashlar = require "ashlar"
local models = require "ashlar.models"
-- script_support.lua lives in this script's folder.
package.path = (arg[0]:match("^(.*)/[^/]+$") or ".") .. "/?.lua;" .. package.path
local support = require "script_support"

local folder, pages = support.output_folders("docs/figures/viewer")
print("pages in " .. pages)
local pictures = support.can_screenshot()
if not pictures then print("chromium not found: only the .html pages are written") end

local timed = support.timed

local function page(name, s, options, no_picture)
  local html = ("%s/%s.html"):format(pages, name)
  timed("export " .. name .. ".html", function() ashlar.export(s, html, options) end)
  local file = assert(io.open(html, "rb"))
  print(("  %s.html: %.2f MB"):format(name, file:seek("end") / 1e6))
  file:close()
  if pictures and not no_picture then
    -- chromium needs an absolute file:// address.
    if html:sub(1, 1) ~= "/" then html = os.getenv("PWD") .. "/" .. html end
    timed("screenshot " .. name .. ".png", function()
      support.screenshot(html, ("%s/%s.png"):format(folder, name), 1000, 640)
    end)
  end
end

print("arch, 15 voussoirs")
local arch = models.arch{ voussoirs = 15 }
-- Planar: the page opens in the front view, orthographic.
arch:set_planar(true)
local r = timed("analyze", function() return ashlar.analyze(arch, { friction = 0.7 }) end)
-- Arrows long enough to read at this size: a round number of newtons per
-- metre of arrow (1, 2 or 5 x 10^k), the largest arrow at most 1 m.
local largest = 0
for _, f in ipairs(r.interfaces) do
  largest = math.max(largest, math.sqrt(f.resultant[1] ^ 2 + f.resultant[2] ^ 2 + f.resultant[3] ^ 2))
end
local decade = 10 ^ math.floor(math.log(largest, 10))
local per_metre = 10 * decade
for _, step in ipairs{ 5, 2, 1 } do
  if step * decade >= largest then per_metre = step * decade end
end
page("arch_forces", arch, { result = r, forces = true, thrust = true, interfaces = true, force_scale = 1 / per_metre,
                            title = "Semicircular arch, 15 voussoirs: interfaces, force resultants, thrust line" })

print("dome, 12 meridians x 8 parallels")
local dome = models.dome{ meridians = 12, parallels = 8 }
local weights = timed("important_weights", function() return ashlar.important_weights(dome) end)
local shown, hi = {}, 0
for i = 1, #dome do
  shown[i] = weights[i] / 1000  -- kN/m^3; supports 0
  hi = math.max(hi, shown[i])
end
page("dome_weights", dome, { color = { values = shown, map = "viridis", range = { 0, hi } },
                             legend = "important weight (kN/m³)",
                             title = "Dome, 12 × 8: which blocks' weight holds it up" })

print("thin dome, 12 meridians x 8 parallels, coloured by tension")
local thin = models.dome{ meridians = 12, parallels = 8, thickness = 0.15 }
local rt = timed("analyze", function() return ashlar.analyze(thin, { friction = 0.7 }) end)
local tension = {}
for i = 1, #thin do tension[i] = rt.blocks[i].tension / 1000 end  -- kN; supports 0
-- No range given: the legend starts at 0, tension being never negative.
page("dome_tension", thin, { color = { values = tension, map = "magma" }, legend = "tension through the block's joints (kN)",
                             title = ("Thin dome, t/R 0.03: the tension equilibrium needs (infeasibility %.3f)"):format(
                               rt.infeasibility) })

print("two-span arcade")
local arcade = models.arch_bridge{ spans = 2, spandrel = false }
local ra = timed("analyze", function() return ashlar.analyze(arcade, { friction = 0.7 }) end)
page("arcade_thrust", arcade, { result = ra, thrust = true,
                                title = "Two-span arcade: the thrust line branches at the pier" })

print("groin vault")
local vault = models.groin_vault{}
local rv = timed("analyze", function() return ashlar.analyze(vault, { friction = 0.7 }) end)
page("groin_vault_network", vault, { result = rv, thrust = true, opacity = 0.25,
                                     title = ("Groin vault, %d blocks: the thrust network (tube thickness: force)"):format(#vault) })

print("dome, 16 meridians x 18 parallels, with forces (size only)")
local big = models.dome{ meridians = 16, parallels = 18 }
local rb = timed("analyze", function() return ashlar.analyze(big, { friction = 0.7 }) end)
page("dome_16x18_forces", big, { result = rb, forces = true }, true)
page("arch_default_forces", models.arch{}, { result = ashlar.analyze(models.arch{}, { friction = 0.7 }), forces = true }, true)
