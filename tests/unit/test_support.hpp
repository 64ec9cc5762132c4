// Helpers shared by the unit tests.
#pragma once

#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "geometry/block_builders.hpp"

// The message of the ashlar::Error that action throws, or "(no error)".
inline std::string error_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const ashlar::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A shared axis-aligned box block of default density, for building structures.
inline ashlar::BlockPtr box(const ashlar::Vec3& size, const ashlar::Vec3& center) {
  return std::make_shared<const ashlar::Block>(ashlar::make_box(size, center));
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
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
