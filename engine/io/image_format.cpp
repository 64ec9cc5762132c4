#include "io/image_format.hpp"

#include "core/enum_names.hpp"
#include "core/error.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {
namespace {

constexpr EnumNames<ImageFormat, 3> kImageExtensions{
    {{{ImageFormat::png, "png"}, {ImageFormat::svg, "svg"}, {ImageFormat::pdf, "pdf"}}}};

}  // namespace

ImageFormat image_format(const std::string& path, const std::vector<ImageFormat>& allowed,
                         const std::string& what) {
  const std::string extension = file_extension(path);
  std::string listed;
  for (size_t k = 0; k < allowed.size(); ++k) {
    if (extension == kImageExtensions.name(allowed[k])) return allowed[k];
    listed += (k == 0 ? "." : k + 1 == allowed.size() ? " or ." : ", .");
    listed += kImageExtensions.name(allowed[k]);
  }
  throw InvalidArgument(what + ": cannot tell the format of '" + path +
                        "' from its extension; use " + listed);
}

void check_image_size(int width, int height, int least, const std::string& what) {
  for (const int size : {width, height}) {
    if (size < least || size > kMaxImageSize) {
      throw InvalidArgument(what + ": width and height must lie in [" + std::to_string(least) +
                            ", " + std::to_string(kMaxImageSize) + "], got " +
                            std::to_string(width) + " x " + std::to_string(height));
    }
  }
}

}  // namespace ashlar
