// Small text helpers for messages and stored names.
#pragma once

#include <string>
#include <vector>

namespace ashlar {

// "a, b, c" (or with another separator).
inline std::string join(const std::vector<std::string>& parts, const std::string& separator = ", ") {
  std::string text;
  for (std::size_t i = 0; i < parts.size(); ++i) text += (i ? separator : "") + parts[i];
  return text;
}

}  // namespace ashlar
