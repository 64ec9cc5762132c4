// Small text helpers for messages and stored names.
#pragma once

#include <algorithm>
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

// The candidate a misspelt `name` most likely meant: the nearest by edits
// (insertions, deletions, substitutions and swaps of neighbours, each 1),
// if within a third of the name's length (at least 1); "" otherwise.
// "analyse" -> "analyze", "arc" -> "arch".
inline std::string closest_name(const std::string& name, const std::vector<std::string>& candidates) {
  const std::size_t n = name.size();
  std::size_t best = std::max<std::size_t>(1, n / 3) + 1;
  std::string closest;
  for (const std::string& candidate : candidates) {
    const std::size_t m = candidate.size();
    if ((m > n ? m - n : n - m) >= best) continue;
    // Optimal string alignment distance, three rows.
    std::vector<std::size_t> before(m + 1), previous(m + 1), current(m + 1);
    for (std::size_t j = 0; j <= m; ++j) previous[j] = j;
    for (std::size_t i = 1; i <= n; ++i) {
      current[0] = i;
      for (std::size_t j = 1; j <= m; ++j) {
        const std::size_t cost = name[i - 1] == candidate[j - 1] ? 0 : 1;
        current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
        if (i > 1 && j > 1 && name[i - 1] == candidate[j - 2] && name[i - 2] == candidate[j - 1]) {
          current[j] = std::min(current[j], before[j - 2] + 1);
        }
      }
      before.swap(previous);
      previous.swap(current);
    }
    if (previous[m] < best) {
      best = previous[m];
      closest = candidate;
    }
  }
  return closest;
}

}  // namespace ashlar
