-- Pictures of a collapse mechanism: a semicircular arch (centreline radius
-- 1 m, thickness 0.15 m, 64 voussoirs, no sliding) at its load factor
-- under a horizontal body force, drawn from ashlar.load_factor's result.
--   ashlar scripts/mechanism_figures.lua [folder, default docs/figures/mechanisms] [pages]
-- Writes
--   arch_four_hinges.svg / .png   ashlar.draw: the four hinges (dots at their
--                                 pivots), the line of thrust at the factor
--                                 through them, the blocks moved by the
--                                 mechanism (dashed, fastest centroid 0.15 m)
--   arch_four_hinges_viewer.png   the HTML viewer of ashlar.export with the
--                                 same result (headless chromium; skipped
--                                 when it is not installed), the page in
--                                 `pages` (default: a new temporary folder):
--                                 it plays the mechanism; the picture is the
--                                 page as it opens, paused at the extreme
-- and prints the factor and the hinges' joints.
local ashlar = require "ashlar"
local models = require "ashlar.models"
-- script_support.lua lives in this script's folder.
package.path = (arg[0]:match("^(.*)/[^/]+$") or ".") .. "/?.lua;" .. package.path
local support = require "script_support"

local folder, pages = support.output_folders("docs/figures/mechanisms")

local n = 64
local arch = models.arch{ radius = 1, thickness = 0.15, voussoirs = n }
local f = ashlar.load_factor(arch, { friction = math.huge })
local joints = {}
for _, limit in ipairs(f.limit) do
  -- Joint j lies between voussoirs j and j + 1 (0: the left support, n: the right).
  joints[#joints + 1] = ("%d (%s)"):format(limit.b == n + 1 and 0 or limit.a, limit.mode)
end
print(("load factor %.7f, hinges at joints %s"):format(f.factor, table.concat(joints, ", ")))

local title = ("Four-hinge mechanism at load factor %.4f"):format(f.factor)
for _, ext in ipairs{ "svg", "png" } do
  ashlar.draw(arch, ("%s/arch_four_hinges.%s"):format(folder, ext),
              { result = f, mechanism = 0.15, title = title, width = 1200, height = 700 })
end

local html = ("%s/arch_four_hinges.html"):format(pages)
-- Paused as it opens (autoplay = false): the picture is the extreme.
ashlar.export(arch, html, { result = f, mechanism = 0.15, autoplay = false, title = title })
print("page " .. html)
if support.can_screenshot() then
  if html:sub(1, 1) ~= "/" then html = os.getenv("PWD") .. "/" .. html end
  support.screenshot(html, ("%s/arch_four_hinges_viewer.png"):format(folder), 1000, 640)
else
  print("chromium not found: no viewer screenshot")
end
