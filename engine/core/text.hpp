// Small text helpers for messages and stored names.
#pragma once

#include <charconv>
#include <sstream>
#include <string>
#include <vector>

namespace ashlar {

// "a, b, c" (or with another separator).
inline std::string join(const std::vector<std::string>& parts, const std::string& separator = ", ") {
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? separator : "") + parts[i];
  return text;
}

// Significant digits that echo a value the user gave recognisably.
constexpr int kGivenValueDigits = 10;

// A value in a message, to `digits` significant digits: "0.0123" at 3, the
// default for measured values.
inline std::string message_number(double value, int digits = 3) {
  std::ostringstream text;
  text.precision(digits);
  text << value;
  return text.str();
}

// The shortest text that reads back as the same double: "0.2", not
// "0.20000000000000001"; "inf", "-inf" and "nan" for those.
inline std::string shortest_number(double value) {
  char buffer[32];
  const std::to_chars_result end = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end.ptr);
}

}  // namespace ashlar
