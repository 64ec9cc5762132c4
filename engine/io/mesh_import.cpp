// Mesh import through assimp: every scene node that carries polygon meshes
// becomes one block, in world coordinates. Files such as STL repeat each
// vertex per triangle, and assimp's own JoinIdenticalVertices keeps vertices
// with different normals apart, so the raw polygons go to block_from_mesh,
// which welds by position alone, merges coplanar triangles and validates.
//
// Axes: glTF is +Y up by specification, ashlar is +Z up, so glTF/GLB scenes
// are rotated (x, y, z) -> (x, -z, y) on import (the inverse of export).
// Other formats carry no convention and are taken as they are.
#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Core>
#include <assimp/Importer.hpp>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "geometry/block_builders.hpp"
#include "geometry/polygon.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {
namespace {

// One node's meshes joined into a polygon soup in world coordinates.
struct RawObject {
  std::string name;
  std::vector<Vec3> vertices;     // in ashlar's frame (m, z up)
  std::vector<Vec3> file_points;  // the same, as the file gives them
  std::vector<FaceLoop> faces;
};

Eigen::Matrix4d to_matrix(const aiMatrix4x4& m) {
  Eigen::Matrix4d result;
  result << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2,
      m.d3, m.d4;
  return result;
}

// Assimp names nodes it had to invent "<STL_BINARY>", "<PLY_Root>" and the
// like; those say nothing about the object, so they count as no name.
std::string meaningful_name(const aiString& name) {
  const std::string text = name.C_Str();
  if (text.size() >= 2 && text.front() == '<' && text.back() == '>') return {};
  return text;
}

class SceneWalker {
public:
  SceneWalker(const aiScene& scene, bool y_up) : scene_(scene), y_up_(y_up) {}

  std::vector<RawObject> objects(const aiNode& root) {
    walk(root, Eigen::Matrix4d::Identity());
    return std::move(objects_);
  }

private:
  void walk(const aiNode& node, const Eigen::Matrix4d& parent_to_world) {
    const Eigen::Matrix4d to_world = parent_to_world * to_matrix(node.mTransformation);
    if (node.mNumMeshes > 0) add_object(node, to_world);
    for (unsigned c = 0; c < node.mNumChildren; ++c) walk(*node.mChildren[c], to_world);
  }

  Vec3 world_point(const Eigen::Matrix4d& to_world, const aiVector3D& p) const {
    const Vec3 q = (to_world * Eigen::Vector4d(p.x, p.y, p.z, 1.0)).head<3>();
    return y_up_ ? Vec3(q.x(), -q.z(), q.y()) : q;
  }

  void add_object(const aiNode& node, const Eigen::Matrix4d& to_world) {
    RawObject object;
    object.name = meaningful_name(node.mName);
    for (unsigned m = 0; m < node.mNumMeshes; ++m) {
      const aiMesh& mesh = *scene_.mMeshes[node.mMeshes[m]];
      if (object.name.empty()) object.name = meaningful_name(mesh.mName);
      const int offset = static_cast<int>(object.vertices.size());
      for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
        const aiVector3D& p = mesh.mVertices[v];
        object.vertices.push_back(world_point(to_world, p));
        object.file_points.emplace_back(p.x, p.y, p.z);
      }
      for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
        const aiFace& face = mesh.mFaces[f];
        // Points and lines (e.g. OBJ "l" records) bound no volume.
        if (face.mNumIndices < 3) continue;
        FaceLoop loop(face.mIndices, face.mIndices + face.mNumIndices);
        for (int& index : loop) index += offset;
        object.faces.push_back(std::move(loop));
      }
    }
    if (object.faces.empty()) return;
    if (object.name.empty()) object.name = "object " + std::to_string(objects_.size() + 1);
    objects_.push_back(std::move(object));
  }

  const aiScene& scene_;
  bool y_up_;
  std::vector<RawObject> objects_;
};

// Repeated names get "#2", "#3", ... so that every block keeps its own name.
void make_names_unique(std::vector<RawObject>& objects) {
  std::map<std::string, int> uses;
  for (const RawObject& object : objects) uses[object.name] = 0;
  for (RawObject& object : objects) {
    int& count = uses[object.name];
    if (++count == 1) continue;
    std::string candidate;
    do {
      candidate = object.name + "#" + std::to_string(count++);
    } while (uses.count(candidate) > 0);
    uses[candidate] = 1;
    object.name = candidate;
  }
}

// assimp reads coordinates as 32-bit floats: far from the origin, or for a
// tiny object, their steps are coarse against the object's size, and points
// merge or faces bend. Such a failure says so.
std::string single_precision_note(const std::vector<Vec3>& vertices) {
  Box3 box;
  double farthest = 0.0;
  for (const Vec3& v : vertices) {
    if (!v.allFinite()) return {};
    box.add(v);
    farthest = std::max(farthest, v.cwiseAbs().maxCoeff());
  }
  const double step = farthest * std::numeric_limits<float>::epsilon();
  const double size = (box.hi - box.lo).stableNorm();
  if (!(step > 1e-6 * size)) return {};
  std::ostringstream note;
  note.precision(3);
  note << "; mesh files are read in single precision, in steps of about " << step
       << " m this far from the origin, coarse for an object " << size
       << " m across: expected coordinates near the origin, in metres";
  return note.str();
}

bool is_separator(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\0';
}

// assimp 5.2's PLY reader never returns on a header without an end_header
// line: at the end of the file it asks for the next line forever. It takes
// any file whose first three bytes read "ply" in any case, whatever its
// extension, so such files are refused here, before assimp reads them.
bool is_ply_without_end_header(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  char magic[3] = {};
  file.read(magic, 3);
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  if (file.gcount() < 3 || lower(magic[0]) != 'p' || lower(magic[1]) != 'l' || lower(magic[2]) != 'y') {
    return false;
  }
  const std::string end_header = "end_header";
  std::string line;
  while (std::getline(file, line)) {
    const std::size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line.compare(start, end_header.size(), end_header) != 0) continue;
    const std::size_t after = start + end_header.size();
    if (after == line.size() || is_separator(line[after])) return false;
  }
  return true;
}

void check_options(const ImportOptions& options) {
  if (!std::isfinite(options.density) || options.density <= 0) {
    std::ostringstream message;
    message << "import: density must be a positive number (kg/m^3), got " << options.density;
    throw InvalidArgument(message.str());
  }
  if (!std::isfinite(options.relative_weld_tolerance) || options.relative_weld_tolerance < 0) {
    std::ostringstream message;
    message << "import: relative_weld_tolerance must be a number >= 0, got "
            << options.relative_weld_tolerance;
    throw InvalidArgument(message.str());
  }
}

// The file system as ImportOptions::may_open lets assimp see it.
class GuardedFiles : public Assimp::DefaultIOSystem {
public:
  explicit GuardedFiles(std::function<bool(const std::string&)> may_open) : may_open_(std::move(may_open)) {}
  bool Exists(const char* file) const override { return may_open_(file) && DefaultIOSystem::Exists(file); }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    return may_open_(file) ? DefaultIOSystem::Open(file, mode) : nullptr;
  }

private:
  std::function<bool(const std::string&)> may_open_;
};

}  // namespace

std::vector<ImportedBlock> import_blocks(const std::string& path, const ImportOptions& options) {
  check_options(options);
  if (is_ply_without_end_header(path)) {
    throw IoError("cannot import '" + path + "': its PLY header has no end_header line");
  }
  Assimp::Importer importer;
  if (options.may_open) importer.SetIOHandler(new GuardedFiles(options.may_open));  // the importer owns it
  // No JoinIdenticalVertices and no Triangulate: welding is by position in
  // block_from_mesh, and polygon faces are kept as they are.
  const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    throw IoError("cannot import '" + path + "': " + importer.GetErrorString());
  }
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr) {
    throw IoError("cannot import '" + path + "': the file holds no complete scene");
  }

  std::vector<RawObject> objects = SceneWalker(*scene, is_y_up_file(path)).objects(*scene->mRootNode);
  if (objects.empty()) throw IoError("cannot import '" + path + "': it contains no polygon mesh");
  make_names_unique(objects);

  // Non-finite vertices are left to block_from_mesh, which names them; here
  // they would make the tolerance infinite.
  Box3 bounds;
  for (const RawObject& object : objects) {
    for (const Vec3& v : object.vertices) {
      if (v.allFinite()) bounds.add(v);
    }
  }
  const double weld_tolerance =
      bounds.empty() ? 0.0 : options.relative_weld_tolerance * (bounds.hi - bounds.lo).stableNorm();

  std::vector<ImportedBlock> blocks;
  blocks.reserve(objects.size());
  for (const RawObject& object : objects) {
    const BlockStyle style{options.density, object.name, options.planarity};
    const std::string what = "object '" + object.name + "' in '" + path + "'";
    // Formats like OBJ keep no vertex numbers through the reader (it gives
    // each face corner a vertex of its own), so vertices are named by their
    // coordinates in the file, and faces by their order in the object.
    MeshNumbering numbering;
    numbering.vertex_name = [&object](int index) {
      std::ostringstream name;
      const Vec3& p = object.file_points[index];
      name << "vertex (" << p.x() << ", " << p.y() << ", " << p.z() << ")";
      return name.str();
    };
    numbering.face_name = [](int index) { return "face " + std::to_string(index + 1); };
    try {
      blocks.push_back(
          import_object(object.name, object.vertices, object.faces, weld_tolerance, style, what, numbering));
    } catch (const GeometryError& error) {
      throw GeometryError(error.what() + std::string(" (faces counted from 1 in the object's order in the file, "
                                                     "vertices by their coordinates in the file)") +
                          single_precision_note(object.vertices));
    }
  }
  face_plates_to_blocks(blocks);
  return blocks;
}

ImportedBlock import_object(const std::string& name, const std::vector<Vec3>& vertices,
                            const std::vector<FaceLoop>& faces, double weld_tolerance,
                            const BlockStyle& style, const std::string& what,
                            const MeshNumbering& numbering) {
  try {
    return {name, block_from_mesh(vertices, faces, weld_tolerance, style, what, numbering), {}};
  } catch (const GeometryError&) {
    std::optional<std::vector<Vec3>> outline = open_planar_outline(vertices, faces, weld_tolerance, style.planarity);
    if (!outline) throw;
    const Vec3 front = (*outline)[0] + newell_normal(*outline);
    Block plate = support_plate(*outline, front, style);
    return {name, std::move(plate), std::move(*outline)};
  }
}

void face_plates_to_blocks(std::vector<ImportedBlock>& blocks) {
  double volume = 0.0;
  Vec3 moment = Vec3::Zero();
  for (const ImportedBlock& imported : blocks) {
    if (!imported.surface.empty()) continue;
    volume += imported.block.volume();
    moment += imported.block.volume() * imported.block.centroid();
  }
  if (!(volume > 0.0)) return;
  const Vec3 centroid = moment / volume;
  for (ImportedBlock& imported : blocks) {
    if (imported.surface.empty()) continue;
    const BlockStyle style{imported.block.density(), imported.block.name(), imported.block.planarity()};
    imported.block = support_plate(imported.surface, centroid, style);
  }
}

}  // namespace ashlar
