-- Option checking shared by the model generators: unknown keys, types and
-- ranges are errors that name the generator, the key and what is allowed.
local options = {}

-- The most blocks a generator makes, and the most any count option may ask
-- for: a count of 1e9 is a typing mistake, refused before a loop or a table
-- of that size is attempted.
options.MAX_BLOCKS = 1000000

local function fail(generator, message)
  -- Level 4: the caller of the generator (check -> generator -> caller).
  error(("%s: %s"):format(generator, message), 4)
end

-- spec: { key = { type = "number" | "string" | "boolean" | "vec2" | "vec3",
--                 default = value, min = n, max = n, above = n, integer = true,
--                 one_of = { ... } } }
-- Integer options are counts: at most options.MAX_BLOCKS unless max says.
-- Returns a new table with defaults filled in.
function options.check(generator, given, spec)
  if given ~= nil and type(given) ~= "table" then
    fail(generator, "expected an option table, got " .. type(given))
  end
  given = given or {}
  local allowed = {}
  for key in pairs(spec) do allowed[#allowed + 1] = key end
  table.sort(allowed)
  for key in pairs(given) do
    if spec[key] == nil then
      fail(generator, ("unknown option '%s' (allowed: %s)"):format(tostring(key), table.concat(allowed, ", ")))
    end
  end
  local out = {}
  for key, rule in pairs(spec) do
    local value = given[key]
    if value == nil then value = rule.default end
    if value ~= nil then
      if rule.type == "vec2" or rule.type == "vec3" then
        local n = rule.type == "vec2" and 2 or 3
        if type(value) ~= "table" or #value ~= n then
          fail(generator, ("%s: expected a table of %d numbers"):format(key, n))
        end
        for i = 1, n do
          local v = value[i]
          if type(v) ~= "number" or v ~= v or v == math.huge or v == -math.huge then
            fail(generator, ("%s[%d]: expected a finite number"):format(key, i))
          end
          if rule.above and v <= rule.above then
            fail(generator, ("%s[%d]: must be > %g, got %g"):format(key, i, rule.above, v))
          end
        end
      elseif type(value) ~= rule.type then
        fail(generator, ("%s: expected a %s, got %s"):format(key, rule.type, type(value)))
      elseif rule.type == "number" then
        if value ~= value or value == math.huge or value == -math.huge then
          fail(generator, ("%s: expected a finite number"):format(key))
        end
        if rule.integer and math.type(value) ~= "integer" and value ~= math.floor(value) then
          fail(generator, ("%s: expected an integer, got %g"):format(key, value))
        end
        if rule.min and value < rule.min then
          fail(generator, ("%s: must be >= %g, got %g"):format(key, rule.min, value))
        end
        if rule.above and value <= rule.above then
          fail(generator, ("%s: must be > %g, got %g"):format(key, rule.above, value))
        end
        if rule.max and value > rule.max then
          fail(generator, ("%s: must be <= %g, got %g"):format(key, rule.max, value))
        end
        if rule.integer and not rule.max and value > options.MAX_BLOCKS then
          fail(generator, ("%s: must be <= %d (the most blocks a model may have), got %g")
            :format(key, options.MAX_BLOCKS, value))
        end
      elseif rule.one_of then
        local ok = false
        for _, name in ipairs(rule.one_of) do ok = ok or value == name end
        if not ok then
          fail(generator, ("%s: '%s' is not one of %s"):format(key, tostring(value), table.concat(rule.one_of, ", ")))
        end
      end
    end
    out[key] = value
  end
  return out
end

-- For generators whose counts multiply: `count` blocks, as `how` explains
-- (e.g. "meridians x parallels = 16 x 18"), must be at most MAX_BLOCKS.
function options.limit_blocks(generator, count, how)
  if count > options.MAX_BLOCKS then
    fail(generator, ("%s makes %.0f blocks, more than the %d a model may have")
      :format(how, count, options.MAX_BLOCKS))
  end
end

return options
