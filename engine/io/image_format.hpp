// The picture formats of drawings, legends and charts, told by a file's
// extension, and their sizes.
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

// The largest width or height of a picture (px, pt).
constexpr int kMaxImageSize = 16384;

// Throws InvalidArgument "<what>: width and height must lie in [least,
// 16384], got <width> x <height>" unless both do.
void check_image_size(int width, int height, int least, const std::string& what);

}  // namespace ashlar
