// Checks of the options that ashlar.export and ashlar.draw share: colours
// (one per block, or single ones), and an analysis result that must be of the structure being drawn.
// `caller` ("export", "draw") begins every message.
#pragma once

#include <string>
#include <vector>

#include "io/mesh_io.hpp"

namespace ashlar {

// Throws InvalidArgument unless every component lies in [0, 1]; `what`
// names the colour.
void check_color(const Rgb& color, const std::string& what, const std::string& caller);

// Throws InvalidArgument unless the structure has blocks and `colors` is
// empty or holds one valid colour per block.
void check_block_colors(const Structure& structure, const std::vector<Rgb>& colors,
                        const std::string& caller);

// Throws InvalidArgument when forces or thrust are asked for without a
// result, or when `result` is of another structure: other block count, or
// other interfaces (pairs of blocks) than structure.interfaces(contact).
void check_result_of_structure(const Structure& structure, const EquilibriumResult* result,
                               bool forces, bool thrust, const ContactOptions& contact,
                               const std::string& caller);

}  // namespace ashlar
