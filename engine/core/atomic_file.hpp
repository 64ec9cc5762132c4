// Whole-or-nothing file writes: data goes to a temporary file in the target's
// folder, is flushed, then renamed over the target.
#pragma once

#include <string>

namespace ashlar {

// Throws IoError naming the path on any failure; the target is untouched then.
void write_file_atomically(const std::string& path, const std::string& contents);

// One file of a set written together (e.g. a .gltf and its .bin): the
// constructor writes and flushes the contents under a temporary name beside
// `path`, commit() renames it over `path`. Writing every file of the set
// before committing any means a failure while writing leaves no file
// changed. An uncommitted file's temporary is removed by the destructor.
// Both throw IoError naming the path.
class StagedFile {
public:
  StagedFile(std::string path, const std::string& contents);
  ~StagedFile();
  StagedFile(StagedFile&& other) noexcept;
  StagedFile(const StagedFile&) = delete;
  StagedFile& operator=(const StagedFile&) = delete;
  StagedFile& operator=(StagedFile&&) = delete;

  void commit();
  const std::string& path() const { return path_; }

private:
  std::string path_;
  std::string temp_path_;  // empty once committed or moved from
};

// Reads a whole file; throws IoError naming the path.
std::string read_file(const std::string& path);

}  // namespace ashlar
