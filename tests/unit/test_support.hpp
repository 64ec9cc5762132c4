// Helpers shared by the unit tests.
#pragma once

#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "geometry/block_builders.hpp"
#include "structure/structure.hpp"

// The message of the ashlar::Error that action throws, or "(no error)".
inline std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const ashlar::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Analysis settings with friction coefficient mu, the rest at defaults.
inline ashlar::AnalysisSettings with_friction(double mu) {
  ashlar::AnalysisSettings settings;
  settings.problem.friction = mu;
  return settings;
}

// A shared axis-aligned box block of default density, for building structures.
inline ashlar::BlockPtr box(const ashlar::Vec3& size, const ashlar::Vec3& center) {
  return std::make_shared<const ashlar::Block>(ashlar::make_box(size, center));
}

// A semicircular arch of `count` voussoirs (centreline radius 5 m,
// thickness t, depth 1 m, x-z plane) on two support blocks.
inline ashlar::Structure semicircular_arch(int count, double thickness) {
  using ashlar::Vec3;
  const double inner = 5.0 - thickness / 2, outer = 5.0 + thickness / 2;
  auto joint = [&](double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return std::vector<Vec3>{{outer * c, -0.5, outer * s}, {inner * c, -0.5, inner * s},
                             {inner * c, 0.5, inner * s}, {outer * c, 0.5, outer * s}};
  };
  ashlar::Structure s;
  for (int k = 0; k < count; ++k) {
    const double a = M_PI * (1.0 - static_cast<double>(k) / count);
    const double b = M_PI * (1.0 - static_cast<double>(k + 1) / count);
    s.add(std::make_shared<const ashlar::Block>(ashlar::make_loft(joint(a), joint(b))));
  }
  s.add(box({2 * thickness, 1, 1}, {-5, 0, -0.5}), true);
  s.add(box({2 * thickness, 1, 1}, {5, 0, -0.5}), true);
  return s;
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The text of each <text> element of an SVG that PLplot's svg driver wrote,
// which writes every character as &#xHH; and a superscript as a <tspan>
// raised by dy < 0: "10^-6" for 10 with -6 raised.
inline std::vector<std::string> svg_texts(const std::string& svg) {
  std::vector<std::string> texts;
  for (size_t at = svg.find("<text"); at != std::string::npos; at = svg.find("<text", at + 1)) {
    const size_t end = svg.find("</text>", at);
    std::string text;
    for (size_t k = at; k < end; ++k) {
      if (svg.compare(k, 12, "<tspan dy=\"-") == 0) text += '^';
      if (svg.compare(k, 3, "&#x") != 0) continue;
      const unsigned long code = std::stoul(svg.substr(k + 3, svg.find(';', k) - k - 3), nullptr, 16);
      // UTF-8 of the code point (the labels here are below U+10000).
      if (code < 0x80) {
        text += static_cast<char>(code);
      } else if (code < 0x800) {
        text += static_cast<char>(0xc0 | (code >> 6));
        text += static_cast<char>(0x80 | (code & 0x3f));
      } else {
        text += static_cast<char>(0xe0 | (code >> 12));
        text += static_cast<char>(0x80 | ((code >> 6) & 0x3f));
        text += static_cast<char>(0x80 | (code & 0x3f));
      }
    }
    texts.push_back(text);
  }
  return texts;
}

inline bool has_text(const std::vector<std::string>& texts, const std::string& text) {
  return std::find(texts.begin(), texts.end(), text) != texts.end();
}

// A fresh folder under /tmp for one test, removed with its files afterwards.

class TempDir {
public:
  TempDir() {
    char pattern[] = "/tmp/ashlar-test-XXXXXX";
    path_ = ::mkdtemp(pattern);
  }
  ~TempDir() {
    for (const auto& name : entries()) ::unlink(file(name).c_str());
    ::rmdir(path_.c_str());
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return path_ + "/" + name; }

  // Names of the folder's entries, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    if (DIR* dir = ::opendir(path_.c_str())) {
      while (const dirent* entry = ::readdir(dir)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..") names.push_back(name);
      }
      ::closedir(dir);
    }
    std::sort(names.begin(), names.end());
    return names;
  }

private:
  std::string path_;
};
