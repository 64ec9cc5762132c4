// Named triangle meshes written as one 3D file through assimp's exporters
// (glTF 2.0, OBJ, PLY, STL; the extension picks the format), whole or not at
// all. Every export to a mesh file goes through here, so formats, axes,
// materials and atomic writing are decided once.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "geometry/block.hpp"
#include "io/flat_mesh.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {

// Collects objects (a node with one mesh and a material of its own each)
// and writes them as one scene.
//
// Axes: glTF is +Y up by specification, so positions and normals are
// rotated (x, y, z) -> (x, z, -y) for .gltf/.glb; import rotates back.
// Assimp stores single-precision floats, so files carry about 7 significant
// digits.
class SceneWriter {
public:
  // The format comes from the extension of `path` (export_extensions());
  // throws InvalidArgument for any other, the message beginning with
  // `caller` and listing the supported ones.
  SceneWriter(std::string path, const std::string& caller);
  ~SceneWriter();
  SceneWriter(const SceneWriter&) = delete;
  SceneWriter& operator=(const SceneWriter&) = delete;

  // `opacity` in [0, 1]: below 1 the glTF writer turns on alpha blending;
  // PLY and STL have no materials.
  void add_object(const std::string& name, const FlatMesh& mesh, const Rgb& color, bool two_sided,
                  double opacity = 1.0);
  // Writes the file with its companions (.bin, .mtl), the objects children
  // of a root node `root_name`; throws IoError on failure, leaving no file
  // changed. Once only.
  void write(const std::string& root_name);

private:
  struct Scene;
  std::string path_;
  bool y_up_;
  const char* assimp_id_;
  std::unique_ptr<Scene> scene_;
};

}  // namespace ashlar
