// Whole-or-nothing file writes: data goes to a temporary file in the target's
// folder, is flushed, then renamed over the target.
#pragma once

#include <string>

namespace ashlar {

// Throws IoError naming the path on any failure; the target is untouched then.
void write_file_atomically(const std::string& path, const std::string& contents);

// Reads a whole file; throws IoError naming the path.
std::string read_file(const std::string& path);

}  // namespace ashlar
