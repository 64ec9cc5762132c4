// Small text helpers for messages and stored names.
#pragma once

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

// A measured value in an error message, to 3 significant digits: "0.0123".
inline std::string message_number(double value) {
  std::ostringstream text;
  text.precision(3);
  text << value;
  return text.str();
}

}  // namespace ashlar
