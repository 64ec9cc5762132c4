// One table per enum, used both ways: the name a script writes for each
// value, and the value a name stands for.
//   constexpr EnumNames<Mode, 2> kModeNames{{{{Mode::a, "a"}, {Mode::b, "b"}}}};
//   kModeNames.name(Mode::a) == "a";  kModeNames.parse("b") == Mode::b
#pragma once

#include <array>
#include <cstddef>
#include <cstring>
#include <optional>
#include <string>
#include <utility>

namespace ashlar {

template <class Enum, std::size_t Count>
struct EnumNames {
  std::array<std::pair<Enum, const char*>, Count> entries;

  const char* name(Enum value) const {
    for (const auto& [entry, text] : entries) {
      if (entry == value) return text;
    }
    return "?";
  }
  std::optional<Enum> parse(const std::string& text) const {
    for (const auto& [entry, name] : entries) {
      if (text == name) return entry;
    }
    return std::nullopt;
  }
  // "a, b, c", for messages.
  std::string list() const {
    std::string names;
    for (const auto& entry : entries) names += (names.empty() ? "" : ", ") + std::string(entry.second);
    return names;
  }
};

}  // namespace ashlar
