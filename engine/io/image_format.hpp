// The picture formats of drawings and charts, told by a file's extension.
#pragma once

#include <string>
#include <vector>

namespace ashlar {

enum class ImageFormat { png, svg, pdf };

// The format of `path` from its extension (any case), one of `allowed`.
// Throws InvalidArgument "<what>: cannot tell the format of '<path>' from its
// extension; use .svg or .png", listing the allowed ones in their order.
ImageFormat image_format(const std::string& path, const std::vector<ImageFormat>& allowed,
                         const std::string& what);

}  // namespace ashlar
