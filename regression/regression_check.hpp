// The checks of a regression suite: the values that a check script records
// with `check(name, value, opts)` (`require "ashlar.regression"`), how they
// are compared with golden and reference values, and how they print.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <lua.hpp>

namespace ashlar::regression {

// A recorded value: a number, a boolean, a string or a list of numbers.
// Numbers are finite (a golden file cannot hold NaN or infinity).
using Value = std::variant<double, bool, std::string, std::vector<double>>;

// Numbers agree when |got - expected| <= max(relative |expected|, absolute),
// element by element for lists. Booleans and strings must be equal.
struct Tolerance {
  double relative = 0.0;
  double absolute = 0.0;
};

// The defaults of `check`'s options: tight enough to catch any change of a
// result, loose enough for the last digits that compilers and libraries move.
constexpr double kDefaultRelativeTolerance = 1e-9;

struct Check {
  std::string name;
  std::string where;  // "file.lua:12": the line that recorded it
  Value value;
  Tolerance tolerance{kDefaultRelativeTolerance, 0.0};  // against the golden value
  // An independent value (published, closed-form) that the check must stay
  // near whatever the golden file says, so that a wrong value can never be
  // made golden.
  std::optional<Value> reference;
  Tolerance reference_tolerance;
};

// Why `got` differs from the golden value beyond `tolerance`, e.g. "golden
// 0.5, got 0.6: relative difference 0.2 > tolerance 1e-09"; nullopt when
// they agree.
std::optional<std::string> golden_mismatch(const Value& golden, const Value& got, const Tolerance& tolerance);

// Why the check's value departs from its reference, in the same form;
// nullopt when it has none or stays within reference_tolerance.
std::optional<std::string> reference_mismatch(const Check& check);

// A number with 17 significant digits: it reads back as the same double
// whatever the reader, as a golden file must.
std::string format_number(double number);
// A string quoted and escaped as JSON.
std::string quote(const std::string& text);
// A value for messages: numbers with the fewest digits that read back as
// the same double, strings quoted, long lists cut short.
std::string format_value(const Value& value);

// The checks of one script, in the order recorded. With `echo`, each check
// is also printed as it is recorded (running a check script on its own).
class CheckRecorder {
public:
  explicit CheckRecorder(bool echo = false) : echo_(echo) {}
  // Throws std::runtime_error when the name was recorded before.
  void add(Check check);
  const std::vector<Check>& checks() const { return checks_; }

private:
  bool echo_;
  std::vector<Check> checks_;
};

// Makes `require "ashlar.regression"` return the `check` function, which
// records into `recorder` (it must outlive the state).
void preload_regression_module(lua_State* L, CheckRecorder& recorder);

}  // namespace ashlar::regression
