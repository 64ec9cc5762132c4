// The structure file format (JSON), documented in docs/structure-format.md.
#pragma once

#include <string>

#include "structure/structure.hpp"

namespace ashlar {

constexpr int kStructureFormatVersion = 1;

std::string structure_to_json(const Structure& structure);
// Throws IoError naming the path and the offending entry. planarity: the
// warp of faces accepted (see Block) in blocks that do not carry their own
// "planarity" (saved with blocks that were accepted with one).
Structure structure_from_json(const std::string& text, const std::string& source_name,
                              double planarity = 0.0);

void save_structure(const Structure& structure, const std::string& path);  // atomic
Structure load_structure(const std::string& path, double planarity = 0.0);

}  // namespace ashlar
