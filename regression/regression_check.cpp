#include "regression_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/text.hpp"
#include "luax.hpp"

namespace ashlar::regression {

namespace {

using lua::ArgError;

// Differences and tolerances in messages: enough digits to compare.
std::string format_short(double number) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", number);
  return text;
}


std::string format_option(double number) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", number);
  return text;
}

const char* kind_of(const Value& value) {
  static const char* const kinds[] = {"a number", "a boolean", "a string", "a list of numbers"};
  return kinds[value.index()];
}

bool is_numeric(const Value& value) {
  return std::holds_alternative<double>(value) || std::holds_alternative<std::vector<double>>(value);
}

double allowed_difference(double expected, const Tolerance& tolerance) {
  return std::max(tolerance.relative * std::fabs(expected), tolerance.absolute);
}

// Infinite when expected is 0 and got is not.
double relative_difference(double expected, double got) {
  const double difference = std::fabs(got - expected);
  if (difference == 0.0) return 0.0;
  return expected == 0.0 ? std::numeric_limits<double>::infinity() : difference / std::fabs(expected);
}

// The option names that set a tolerance, so that a message says what to
// change: "tolerance" and "absolute" for the golden value,
// "reference_tolerance" and "reference_absolute" for the reference.
struct ToleranceNames {
  const char* relative;
  const char* absolute;
};

std::string number_mismatch(double expected, double got, const Tolerance& tolerance,
                            const std::string& label, const ToleranceNames& names) {
  std::string text = label + " " + shortest_number(expected) + ", got " + shortest_number(got) +
                     ": relative difference " + format_short(relative_difference(expected, got));
  if (tolerance.absolute > 0.0) text += ", difference " + format_short(std::fabs(got - expected));
  text += std::string(" > ") + names.relative + " " + format_option(tolerance.relative);
  if (tolerance.absolute > 0.0) text += std::string(", ") + names.absolute + " " + format_option(tolerance.absolute);
  return text;
}

std::optional<std::string> list_mismatch(const std::vector<double>& expected, const std::vector<double>& got,
                                         const Tolerance& tolerance, const std::string& label,
                                         const ToleranceNames& names) {
  if (expected.size() != got.size()) {
    return label + " has " + std::to_string(expected.size()) + " numbers, got " +
           std::to_string(got.size());
  }
  // The element furthest beyond what its tolerance allows stands for all.
  size_t worst = 0, differing = 0;
  double worst_excess = 0.0;
  for (size_t i = 0; i < expected.size(); ++i) {
    const double difference = std::fabs(got[i] - expected[i]);
    const double allowed = allowed_difference(expected[i], tolerance);
    if (difference <= allowed) continue;
    const double excess = allowed > 0.0 ? difference / allowed : std::numeric_limits<double>::infinity();
    if (differing == 0 || excess > worst_excess) worst = i, worst_excess = excess;
    ++differing;
  }
  if (differing == 0) return std::nullopt;
  std::string text = "element " + std::to_string(worst + 1) + " of " + std::to_string(expected.size()) +
                     ": " + number_mismatch(expected[worst], got[worst], tolerance, label, names);
  if (differing > 1) text += " (" + std::to_string(differing) + " elements differ)";
  return text;
}

std::optional<std::string> mismatch(const Value& expected, const Value& got, const Tolerance& tolerance,
                                    const std::string& label, const ToleranceNames& names) {
  if (expected.index() != got.index()) {
    return label + " " + format_value(expected) + " (" + kind_of(expected) + "), got " +
           format_value(got) + " (" + kind_of(got) + ")";
  }
  if (const auto* number = std::get_if<double>(&expected)) {
    const double got_number = std::get<double>(got);
    if (std::fabs(got_number - *number) <= allowed_difference(*number, tolerance)) return std::nullopt;
    return number_mismatch(*number, got_number, tolerance, label, names);
  }
  if (const auto* list = std::get_if<std::vector<double>>(&expected))
    return list_mismatch(*list, std::get<std::vector<double>>(got), tolerance, label, names);
  if (expected == got) return std::nullopt;
  return label + " " + format_value(expected) + ", got " + format_value(got);
}

// ---------------------------------------------------------------------------
// The Lua side: check(name, value, opts)

bool is_valid_utf8(const std::string& text) {
  try {
    (void)nlohmann::json(text).dump();
    return true;
  } catch (const nlohmann::json::type_error&) {
    return false;
  }
}

std::string describe_non_finite(double number) {
  return std::isnan(number) ? "nan" : number > 0 ? "inf" : "-inf";
}

// A golden file keeps finite numbers only; an outcome such as "no factor"
// is better recorded as a status string or a boolean.
constexpr const char* kFiniteOnly = " (golden values are finite: record a status or a boolean instead)";

double read_finite_number(lua_State* L, int index, int arg, const std::string& what) {
  const double number = lua_tonumber(L, index);
  if (!std::isfinite(number))
    throw ArgError(arg, what + ": expected a finite number, got " + describe_non_finite(number) + kFiniteOnly);
  return number;
}

std::vector<double> read_number_list(lua_State* L, int index, int arg, const std::string& what) {
  const lua_Unsigned length = lua_rawlen(L, index);
  lua_Unsigned entries = 0;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    lua_pop(L, 1);
    ++entries;
  }
  if (entries != length)
    throw ArgError(arg, what + ": expected a list of numbers, got a table with keys other than 1.." +
                            std::to_string(length));
  std::vector<double> numbers;
  numbers.reserve(length);
  for (lua_Unsigned k = 1; k <= length; ++k) {
    const std::string element = what + "[" + std::to_string(k) + "]";
    if (lua_rawgeti(L, index, static_cast<lua_Integer>(k)) != LUA_TNUMBER)
      throw ArgError(arg, element + ": expected a number, got " + lua::type_name(L, -1));
    numbers.push_back(read_finite_number(L, -1, arg, element));
    lua_pop(L, 1);
  }
  return numbers;
}

// The value at stack index `index`; errors are about argument `arg` of
// check and name the value `what`.
Value read_value(lua_State* L, int index, int arg, const std::string& what) {
  index = lua_absindex(L, index);
  switch (lua_type(L, index)) {
    case LUA_TNUMBER:
      return read_finite_number(L, index, arg, what);
    case LUA_TBOOLEAN:
      return lua_toboolean(L, index) != 0;
    case LUA_TSTRING: {
      size_t length = 0;
      const char* text = lua_tolstring(L, index, &length);
      std::string value(text, length);
      if (!is_valid_utf8(value)) throw ArgError(arg, what + ": the string is not valid UTF-8");
      return value;
    }
    case LUA_TTABLE:
      return read_number_list(L, index, arg, what);
    default:
      throw ArgError(arg, what + ": expected a number, boolean, string or list of numbers, got " +
                              lua::type_name(L, index));
  }
}

// "file.lua:12" for the Lua function that called check, with the whole
// path (short_src cuts long ones).
std::string caller_position(lua_State* L) {
  lua_Debug caller;
  if (lua_getstack(L, 1, &caller) == 0 || lua_getinfo(L, "Sl", &caller) == 0) return "?";
  const std::string file = caller.source[0] == '@' ? caller.source + 1 : caller.short_src;
  return file + ":" + std::to_string(caller.currentline);
}

void read_reference(const lua::OptionTable& options, Check& check) {
  lua_State* L = options.state();
  const int arg = options.arg();
  const bool has_tolerance = options.has("reference_tolerance") || options.has("reference_absolute");
  if (options.push("reference") == LUA_TNIL) {
    lua_pop(L, 1);
    if (has_tolerance)
      throw ArgError(arg, "reference_tolerance and reference_absolute: only with a reference");
    return;
  }
  Value reference = read_value(L, -1, arg, "reference");
  lua_pop(L, 1);
  if (reference.index() != check.value.index())
    throw ArgError(arg, std::string("reference: expected ") + kind_of(check.value) + " like the value, got " +
                            kind_of(reference));
  const auto* list = std::get_if<std::vector<double>>(&reference);
  if (list && list->size() != std::get<std::vector<double>>(check.value).size())
    throw ArgError(arg, "reference: has " + std::to_string(list->size()) + " numbers, the value " +
                            std::to_string(std::get<std::vector<double>>(check.value).size()));
  if (is_numeric(reference) && !has_tolerance)
    throw ArgError(arg, "reference: give reference_tolerance (relative) or reference_absolute, or both");
  if (!is_numeric(reference) && has_tolerance)
    throw ArgError(arg, std::string("reference_tolerance and reference_absolute: only for numbers, the value is ") +
                            kind_of(check.value));
  check.reference_tolerance.relative = options.positive("reference_tolerance", 0.0, true);
  check.reference_tolerance.absolute = options.positive("reference_absolute", 0.0, true);
  check.reference = std::move(reference);
}

Check read_check(lua_State* L) {
  Check check;
  check.name = lua::check_string(L, 1, "name");
  if (check.name.empty()) throw ArgError(1, "name: expected a non-empty string");
  if (!is_valid_utf8(check.name)) throw ArgError(1, "name: the string is not valid UTF-8");
  check.where = caller_position(L);
  check.value = read_value(L, 2, 2, quote(check.name));
  const lua::OptionTable options(
      L, 3, {"tolerance", "absolute", "reference", "reference_tolerance", "reference_absolute"});
  if (!is_numeric(check.value) && (options.has("tolerance") || options.has("absolute")))
    throw ArgError(3, std::string("tolerance and absolute: only for numbers, the value is ") + kind_of(check.value));
  check.tolerance.relative = options.positive("tolerance", kDefaultRelativeTolerance, true);
  check.tolerance.absolute = options.positive("absolute", 0.0, true);
  read_reference(options, check);
  return check;
}

// check(name, value, opts) --> value
int check_function(lua_State* L) {
  auto& recorder = *static_cast<CheckRecorder*>(lua_touserdata(L, lua_upvalueindex(1)));
  return lua::guard(L, [&] {
    recorder.add(read_check(L));
    lua_settop(L, 2);
    return 1;
  });
}

int open_regression_module(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushcclosure(L, check_function, 1);
  return 1;
}

}  // namespace

std::string format_number(double number) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", number);
  return text;
}

std::string quote(const std::string& text) {
  // Invalid UTF-8 never gets here: names and values are checked on entry.
  return nlohmann::json(text).dump();
}

std::string format_value(const Value& value) {
  if (const auto* number = std::get_if<double>(&value)) return shortest_number(*number);
  if (const auto* boolean = std::get_if<bool>(&value)) return *boolean ? "true" : "false";
  if (const auto* text = std::get_if<std::string>(&value)) return quote(*text);
  // Long lists are cut: a message names the element that differs anyway.
  constexpr size_t kShownElements = 6;
  const auto& list = std::get<std::vector<double>>(value);
  std::string out = "[";
  for (size_t i = 0; i < list.size() && i < kShownElements; ++i)
    out += (i ? ", " : "") + shortest_number(list[i]);
  if (list.size() > kShownElements) out += ", ... (" + std::to_string(list.size()) + " numbers)";
  return out + "]";
}

std::optional<std::string> golden_mismatch(const Value& golden, const Value& got, const Tolerance& tolerance) {
  return mismatch(golden, got, tolerance, "golden", {"tolerance", "absolute"});
}

std::optional<std::string> reference_mismatch(const Check& check) {
  if (!check.reference) return std::nullopt;
  return mismatch(*check.reference, check.value, check.reference_tolerance, "reference",
                  {"reference_tolerance", "reference_absolute"});
}

void CheckRecorder::add(Check check) {
  for (const Check& earlier : checks_) {
    if (earlier.name == check.name)
      throw std::runtime_error("check " + quote(check.name) + " recorded twice (first at " + earlier.where +
                               "): names must be unique within a script");
  }
  if (echo_) {
    std::string line = check.name + ": " + format_value(check.value);
    if (check.reference) {
      const auto violation = reference_mismatch(check);
      line += violation ? "  FAILS its " + *violation : "  (within its reference " + format_value(*check.reference) + ")";
    }
    std::printf("%s\n", line.c_str());
  }
  checks_.push_back(std::move(check));
}

void preload_regression_module(lua_State* L, CheckRecorder& recorder) {
  lua_getglobal(L, "package");
  lua_getfield(L, -1, "preload");
  lua_pushlightuserdata(L, &recorder);
  lua_pushcclosure(L, open_regression_module, 1);
  lua_setfield(L, -2, "ashlar.regression");
  lua_pop(L, 2);
}

}  // namespace ashlar::regression
