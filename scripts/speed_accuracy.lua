-- The speed-accuracy map: for three questions, the error of the answer
-- against the time it takes, over the model's discretisation and the sides
-- of the friction pyramid, and which model answers to 1 % and to 0.1 %.
--   arch_min_thickness  semicircular arch (R 1), minimum t/R, no sliding,
--                       by ashlar.geometric_factor; voussoirs
--   dome_min_thickness  hemispherical dome (R 5), minimum thickness with
--                       friction 0.7; meridians x parallels, pyramid sides 4, 8, 16
--   arch_load_factor    semicircular arch, t/R 0.15, no sliding, lateral load
--                       factor by ashlar.load_factor; voussoirs
-- Each error is against a much finer model (named in the table). In the
-- plane the pyramid has an edge along each joint's tangent, so its sides do
-- not change an arch's answers (checked below); a dome's they do.
-- Then ashlar.refine picks the coarsest adequate model for each question at
-- tolerances 1 % and 0.1 %, as a user would, without the fine reference.
--   ashlar scripts/speed_accuracy.lua [output folder, default docs/figures/speed_accuracy] [question ...] [--charts]
-- Writes <question>.csv, .png and .svg and speed_accuracy.md in the folder;
-- with --charts, only draws the charts again from the folder's CSVs.
local ashlar = require "ashlar"
local models = require "ashlar.models"
local script_support = require "script_support"

local charts_only = script_support.charts_only()
local output = arg[1] or "docs/figures/speed_accuracy"
local chosen = { table.unpack(arg, 2) }
script_support.make_folders(output)

-- Relative tolerance of the searches, far below the errors being judged.
local SEARCH = 1e-6
local SIDES = { 4, 8, 16 }

local function arch(voussoirs, ratio)
  return models.arch{ radius = 1, thickness = ratio, voussoirs = voussoirs }
end

local QUESTIONS = {
  {
    name = "arch_min_thickness",
    title = "Semicircular arch: minimum thickness t/R (no sliding)",
    unit = "t/R",
    levels = { 6, 8, 10, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256 },
    reference_level = 1024,
    label = function(n) return tostring(n) end,
    sides = { 4 },
    answer = function(n, sides)
      local g = ashlar.geometric_factor(function(t) return arch(n, t) end, 0.15,
                                        { friction = math.huge, friction_sides = sides, tolerance = SEARCH })
      assert(g.status == "converged", "arch_min_thickness: " .. g.status .. " at " .. n)
      return g.minimum
    end,
    refine = { model = function(n) return arch(n, 0.15) end, start = 6, growth = 1.5,
               metric = function(_, n)
                 return ashlar.geometric_factor(function(t) return arch(n, t) end, 0.15,
                                                { friction = math.huge, tolerance = SEARCH }).minimum
               end },
  },
  {
    name = "dome_min_thickness",
    title = "Hemispherical dome (R 5): minimum thickness, friction 0.7",
    unit = "m",
    levels = { { 8, 6 }, { 12, 9 }, { 16, 12 }, { 16, 18 }, { 24, 18 }, { 24, 24 }, { 32, 32 } },
    reference_level = { 48, 48 },
    reference_sides = 16,
    label = function(level) return level[1] .. "x" .. level[2] end,
    sides = SIDES,
    answer = function(level, sides)
      local g = ashlar.geometric_factor(function(t)
        return models.dome{ radius = 5, thickness = t, meridians = level[1], parallels = level[2] }
      end, 0.5, { friction = 0.7, friction_sides = sides, tolerance = SEARCH })
      assert(g.status == "converged", "dome_min_thickness: " .. g.status)
      return g.minimum
    end,
    refine = { model = function(n) return models.dome{ radius = 5, thickness = 0.5, meridians = n, parallels = n } end,
               start = 8, growth = 1.5, max = 48,
               metric = function(_, n)
                 return ashlar.geometric_factor(function(t)
                   return models.dome{ radius = 5, thickness = t, meridians = n, parallels = n }
                 end, 0.5, { friction = 0.7, friction_sides = 16, tolerance = SEARCH }).minimum
               end },
  },
  {
    name = "arch_load_factor",
    title = "Semicircular arch, t/R 0.15: lateral load factor (no sliding)",
    unit = "g",
    levels = { 6, 8, 10, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256, 512 },
    reference_level = 4096,
    label = function(n) return tostring(n) end,
    sides = { 4 },
    answer = function(n, sides)
      local f = ashlar.load_factor(arch(n, 0.15), { friction = math.huge, friction_sides = sides })
      assert(f.status == "optimal", "arch_load_factor: " .. f.status)
      return f.factor
    end,
    refine = { model = function(n) return arch(n, 0.15) end, start = 6, growth = 1.5,
               metric = function(s) return ashlar.load_factor(s, { friction = math.huge }).factor end },
  },
}

-- The answer at one level and its wall time; repeated until 0.2 s have
-- passed so that millisecond answers are timed fairly.
local function timed(question, level, sides)
  local start, runs, value = ashlar.clock(), 0, nil
  repeat
    value = question.answer(level, sides)
    runs = runs + 1
  until ashlar.clock() - start > 0.2
  return value, (ashlar.clock() - start) / runs
end

-- The coarsest level whose error, and every finer level's, is within
-- `within` (levels in order of cost).
local function settled(rows, within)
  local found
  for k = #rows, 1, -1 do
    if math.abs(rows[k].error) > within then break end
    found = rows[k]
  end
  return found
end

-- The chart of a question from its CSV's rows: |error| against time, one
-- line per pyramid (through the levels in order of time), and the 1 % and
-- 0.1 % errors as lines across.
local function chart(question, csv_rows)
  local points, names, lowest, highest = {}, {}, math.huge, 0
  for _, row in ipairs(csv_rows) do
    -- An error of 0 (the reference itself) has no place on a log scale.
    if row.error ~= 0 then
      local name = row.sides .. "-sided pyramid"
      if not names[name] then
        names[name] = true
        names[#names + 1] = name
      end
      points[#points + 1] = { seconds = row.seconds, [name] = math.abs(row.error) }
      lowest, highest = math.min(lowest, row.seconds), math.max(highest, row.seconds)
    end
  end
  for _, line in ipairs{ { "1 % error", 0.01 }, { "0.1 % error", 0.001 } } do
    names[#names + 1] = line[1]
    points[#points + 1] = { seconds = lowest, [line[1]] = line[2] }
    points[#points + 1] = { seconds = highest, [line[1]] = line[2] }
  end
  local first = csv_rows[1]
  script_support.chart(output .. "/" .. question.name, { data = points, x = "seconds", y = names,
    log_x = true, log_y = true, x_label = "wall time of the answer (s)", y_label = "|relative error|",
    title = ("%s; reference %s, %d-sided: %.7g %s"):format(question.title, question.label(question.reference_level),
      question.reference_sides or question.sides[1], first.reference, question.unit) })
end

if charts_only then
  for _, question in ipairs(QUESTIONS) do
    local wanted = #chosen == 0
    for _, name in ipairs(chosen) do wanted = wanted or name == question.name end
    if wanted then
      chart(question, script_support.read_csv(output .. "/" .. question.name .. ".csv"))
      print(("wrote %s/%s.png, .svg"):format(output, question.name))
    end
  end
  return
end

local report = { "# Speed-accuracy map", "",
  "Written by `ashlar scripts/speed_accuracy.lua`. Errors are relative to the fine model named; times are",
  "wall times on the machine that ran the script. *Adequate* is the coarsest model whose error, and every",
  "finer model's in the list, stays within the tolerance.", "" }
local csv_header = "question,level,sides,value,reference,error,seconds"

for _, question in ipairs(QUESTIONS) do
  local wanted = #chosen == 0
  for _, name in ipairs(chosen) do wanted = wanted or name == question.name end
  if wanted then
    local reference_sides = question.reference_sides or question.sides[1]
    local start = ashlar.clock()
    local reference = question.answer(question.reference_level, reference_sides)
    local reference_seconds = ashlar.clock() - start
    question.reference_text = ("%s, %d-sided pyramid: %.7g %s"):format(question.label(question.reference_level),
      reference_sides, reference, question.unit)
    print(("%s: reference %s (%.1f s)"):format(question.name, question.reference_text, reference_seconds))
    local series, csv = {}, { csv_header }
    for _, sides in ipairs(question.sides) do
      local rows = {}
      for _, level in ipairs(question.levels) do
        local value, seconds = timed(question, level, sides)
        local row = { label = question.label(level), value = value, seconds = seconds,
                      error = (value - reference) / reference }
        rows[#rows + 1] = row
        print(("  %-8s %2d sides  %.7g  error %+.3e  %.4f s"):format(row.label, sides, value, row.error, seconds))
        csv[#csv + 1] = ("%s,%s,%d,%.10g,%.10g,%.6e,%.6f"):format(question.name, row.label, sides, value,
          reference, row.error, seconds)
      end
      series[#series + 1] = { sides = sides, rows = rows }
    end
    local csv_path = output .. "/" .. question.name .. ".csv"
    script_support.write_atomically(csv_path, table.concat(csv, "\n") .. "\n")
    chart(question, script_support.read_csv(csv_path))

    report[#report + 1] = ("## %s"):format(question.title)
    report[#report + 1] = ""
    report[#report + 1] = ("Reference: %s (%.1f s). Chart: [%s.png](%s.png), data: %s.csv."):format(
      question.reference_text, reference_seconds, question.name, question.name, question.name)
    report[#report + 1] = ""
    report[#report + 1] = "| pyramid sides | adequate to 1 % | its error | its time | adequate to 0.1 % | its error | its time |"
    report[#report + 1] = "|---|---|---|---|---|---|---|"
    for _, s in ipairs(series) do
      local cells = { tostring(s.sides) }
      for _, within in ipairs{ 0.01, 0.001 } do
        local row = settled(s.rows, within)
        if row then
          cells[#cells + 1] = row.label
          cells[#cells + 1] = ("%+.3f %%"):format(100 * row.error)
          cells[#cells + 1] = ("%.3g s"):format(row.seconds)
        else
          cells[#cells + 1], cells[#cells + 1], cells[#cells + 1] = "none in the list", "", ""
        end
      end
      report[#report + 1] = "| " .. table.concat(cells, " | ") .. " |"
    end
    if #question.sides == 1 then
      -- The claim that the sides do not matter in the plane, checked.
      local level = question.levels[5]
      local four = question.answer(level, 4)
      for _, sides in ipairs{ 8, 16 } do
        local other = question.answer(level, sides)
        assert(math.abs(other - four) <= 1e-5 * math.abs(four),
               ("%s: %d sides give %.9g, 4 give %.9g"):format(question.name, sides, other, four))
      end
      report[#report + 1] = ""
      report[#report + 1] = ("8 and 16 sides give the answer of 4 (at %s, to 1e-5): the arch is planar."):format(
        question.label(level))
    end
    report[#report + 1] = ""
    report[#report + 1] = "`ashlar.refine` from the model's coarsest count, without the reference:"
    report[#report + 1] = ""
    report[#report + 1] = "| tolerance | count chosen | value | error against the reference | counts tried | time |"
    report[#report + 1] = "|---|---|---|---|---|---|"
    for _, tolerance in ipairs{ 0.01, 0.001 } do
      local r = question.refine
      local refined = ashlar.refine(r.model, r.metric, { tolerance = tolerance, start = r.start, growth = r.growth,
                                                         max = r.max or 512 })
      local tried = {}
      for _, h in ipairs(refined.history) do tried[#tried + 1] = tostring(h.count) end
      report[#report + 1] = ("| %g %% | %d%s | %.7g | %+.3f %% | %s | %.2f s |"):format(100 * tolerance, refined.count,
        refined.converged and "" or " (not converged)", refined.value, 100 * (refined.value - reference) / reference,
        table.concat(tried, ", "), refined.seconds)
      print(("  refine %g: count %d, value %.7g (%s)"):format(tolerance, refined.count, refined.value,
        table.concat(tried, " ")))
    end
    report[#report + 1] = ""
  end
end
if #chosen == 0 then
  script_support.write_atomically(output .. "/speed_accuracy.md", table.concat(report, "\n"))
  print("wrote " .. output .. "/speed_accuracy.md")
end
