-- How coarse can each generator's discretisation be? For every model whose
-- main question depends on a count (an arch's minimum thickness, a dome's,
-- a flying buttress's smallest pinnacle), this script bisects the answer at
-- each count in a range and at a fine reference count, and reports
--   coarsest: the smallest count whose answer is within 1% of the reference;
--   settled:  the smallest count from which every count in the range stays
--             within 1% (the answers are not monotone in the count: they
--             depend on how near a joint falls to where the hinge forms).
-- The generators' defaults are the settled counts.
--   ashlar scripts/model_discretisation.lua [output folder, default "."] [study ...] [--charts]
-- Studies: semicircular, pointed, segmental, elliptical, bridge_ring,
-- barrel_vault, groin_vault, flying_buttress, dome (default: all). Writes
-- model_discretisation.csv (one row per count) and a chart of the errors,
-- model_discretisation.png and .svg, in the folder; with --charts, only
-- draws the chart again from the folder's CSV.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"

local WITHIN = 0.01
-- Relative bisection tolerance, far below the 1% being judged.
local TOLERANCE = 1e-5

-- The smallest value of a parameter at which `stands` holds: growing by a
-- quarter from `start` (which must fall) until it stands, then bisection. The bracket
-- stays tight so that thick, finely cut arches (whose voussoirs degenerate)
-- are never built.
local function threshold(stands, start)
  if stands(start) then return nil end
  local low, high = start, 1.25 * start
  while not stands(high) do low, high = high, 1.25 * high end
  while high - low > TOLERANCE * high do
    local middle = (low + high) / 2
    if stands(middle) then high = middle else low = middle end
  end
  return (low + high) / 2
end

local NO_SLIDING = { friction = math.huge }

local function arch_study(name, shape, counts, reference, options)
  return {
    name = name, what = "minimum thickness (no sliding), m", counts = counts, reference = reference,
    answer = function(n)
      return threshold(function(t)
        local o = { shape = shape, voussoirs = n, thickness = t }
        for k, v in pairs(options or {}) do o[k] = v end
        return ashlar.analyze(models.arch(o), NO_SLIDING).stable
      end, 0.02)
    end,
  }
end

local function range(first, last, step)
  local list = {}
  for n = first, last, step or 1 do list[#list + 1] = n end
  return list
end

local STUDIES = {
  semicircular = arch_study("semicircular arch", "semicircular", range(4, 64), 512),
  -- Finer, the radial joints next to the apex cross the vertical apex joint.
  pointed = arch_study("pointed arch", "pointed", range(4, 64, 2), 256),
  segmental = arch_study("segmental arch", "segmental", range(4, 64), 512),
  elliptical = arch_study("elliptical arch", "elliptical", range(4, 64), 512),
  -- models.arch_bridge's arch ring at its defaults, bare.
  bridge_ring = arch_study("arch bridge's ring (segmental, span 8, rise 3)", "segmental", range(4, 64), 512,
                           { span = 8, rise = 3 }),
  barrel_vault = {
    name = "barrel vault", what = "minimum thickness (no sliding), m", counts = range(4, 40), reference = 256,
    answer = function(n)
      return threshold(function(t)
        return ashlar.analyze(models.barrel_vault{ voussoirs = n, thickness = t, courses = 2,
                                                   bond = "running" }, NO_SLIDING).stable
      end, 0.02)
    end,
  },
  groin_vault = {
    name = "groin vault (one course)", what = "minimum thickness (friction 0.7), m", counts = range(4, 40, 2),
    reference = 128,
    answer = function(n)
      return threshold(function(t)
        return ashlar.analyze(models.groin_vault{ voussoirs = n, thickness = t, courses = 1 }).stable
      end, 0.02)
    end,
  },
  flying_buttress = {
    name = "flying buttress", what = "smallest pinnacle (friction 0.7), m", counts = range(8, 96, 4), reference = 256,
    answer = function(n)
      return threshold(function(h)
        return ashlar.analyze(models.flying_buttress{ voussoirs = n, pinnacle_height = h }).stable
      end, 0.25)
    end,
  },
  dome = {
    name = "dome (16 meridians)", what = "minimum thickness (friction 0.7), m", counts = range(4, 32, 2),
    reference = 64,
    answer = function(n)
      return threshold(function(t)
        return ashlar.analyze(models.dome{ parallels = n, thickness = t }).stable
      end, 0.02)
    end,
  },
}
local ORDER = { "semicircular", "pointed", "segmental", "elliptical", "bridge_ring", "barrel_vault", "groin_vault", "flying_buttress", "dome" }

-- The first count from which every later one's |error| is within 1%.
local function settled_count(counts, errors)
  local settled
  for i = #counts, 1, -1 do
    if math.abs(errors[i]) > WITHIN then break end
    settled = counts[i]
  end
  return settled
end

-- The chart from the CSV's rows: one line per study, its error in %
-- against the count, named with its settled count.
local function draw_chart(base, csv_rows)
  local counts, errors, points, names = {}, {}, {}, {}
  for _, row in ipairs(csv_rows) do
    if not counts[row.study] then counts[row.study], errors[row.study] = {}, {} end
    table.insert(counts[row.study], row.count)
    table.insert(errors[row.study], row.relative_error or math.huge)
  end
  for _, key in ipairs(ORDER) do
    if counts[key] then
      local name = ("%s (settled from %s)"):format(STUDIES[key].name, tostring(settled_count(counts[key], errors[key])))
      names[#names + 1] = name
      for i, n in ipairs(counts[key]) do
        if errors[key][i] ~= math.huge then points[#points + 1] = { count = n, [name] = 100 * errors[key][i] } end
      end
    end
  end
  -- The errors that decide (within a few %), the coarsest counts' cut off.
  script_support.chart(base, { data = points, x = "count", y = names, y_range = { -8, 2 },
    title = "Error of the main question's answer against the count, relative to a fine model",
    x_label = "count (voussoirs; dome: parallels)", y_label = "relative error (%)" })
end

local charts_only = script_support.charts_only()
local output = arg[1] or "."
local base = output .. "/model_discretisation"
if charts_only then
  draw_chart(base, script_support.read_csv(base .. ".csv"))
  print(("wrote %s.png, %s.svg from %s.csv"):format(base, base, base))
  return
end
local chosen = {}
for i = 2, #arg do chosen[#chosen + 1] = arg[i] end
if #chosen == 0 then chosen = ORDER end
script_support.make_folders(output)

local rows = { "study,count,answer,relative_error" }
for _, key in ipairs(chosen) do
  local study = assert(STUDIES[key], "unknown study: " .. key)
  local start = ashlar.clock()
  local reference = assert(study.answer(study.reference), study.name .. ": reference bracket failed")
  print(("%s: %s = %.6g at %d (reference)"):format(study.name, study.what, reference, study.reference))
  local errors = {}
  for _, n in ipairs(study.counts) do
    local value = study.answer(n)
    local err = value and (value - reference) / reference or math.huge
    errors[#errors + 1] = err
    print(("  %4d  %-12s %+8.3f%%"):format(n, value and ("%.6g"):format(value) or "bracket", 100 * err))
    rows[#rows + 1] = ("%s,%d,%s,%s"):format(key, n, value and ("%.9g"):format(value) or "",
                                             value and ("%.6g"):format(err) or "")
  end
  local coarsest
  for i, n in ipairs(study.counts) do
    if not coarsest and math.abs(errors[i]) <= WITHIN then coarsest = n end
  end
  local settled = settled_count(study.counts, errors)
  print(("  coarsest within 1%%: %s; settled within 1%% from: %s (%.0f s)"):format(
    tostring(coarsest), tostring(settled), ashlar.clock() - start))
end

script_support.write_atomically(base .. ".csv", table.concat(rows, "\n") .. "\n")
draw_chart(base, script_support.read_csv(base .. ".csv"))
print(("wrote %s.csv, %s.png, %s.svg"):format(base, base, base))
