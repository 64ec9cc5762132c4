// Structure export: mesh files through assimp's exporters (glTF 2.0, OBJ,
// PLY, STL), one node per object of structure_scene.hpp, each with its own
// material; or the HTML viewer (viewer_page.hpp).
//
// Formats, axes (glTF is +Y up) and all-or-nothing writing: assimp_scene.hpp.
// Assimp stores single-precision floats, so mesh files carry about 7
// significant digits; the JSON structure format is the exact one.
#include <string>

#include "core/error.hpp"
#include "core/text.hpp"
#include "io/assimp_scene.hpp"
#include "io/mesh_io.hpp"
#include "io/structure_scene.hpp"
#include "io/viewer_page.hpp"

namespace ashlar {

void export_structure(const Structure& structure, const std::string& path,
                      const ExportOptions& options) {
  const std::string extension = file_extension(path);
  if (extension == "html") {
    write_viewer_page(structure, path, options);
    return;
  }
  bool mesh_file = false;
  for (const std::string& known : export_extensions()) mesh_file = mesh_file || known == "." + extension;
  if (!mesh_file) {
    throw InvalidArgument("export: cannot tell the format of '" + path + "' from its extension; use one of: " +
                          join(export_extensions()) + ", .html");
  }
  SceneWriter writer(path, "export");
  for (const SceneObject& object : structure_scene(structure, options)) {
    writer.add_object(object.name, object.mesh, object.color, object.two_sided, object.opacity);
  }
  writer.write("ashlar structure");
}

}  // namespace ashlar
