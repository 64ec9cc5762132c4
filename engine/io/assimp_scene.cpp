// Scene building and writing through assimp's exporters (glTF 2.0, OBJ,
// PLY, STL), shared by the exports of structures and FEA results.
//
// Atomicity: assimp writes through an IOSystem whose streams collect each
// file in memory. Only when the whole export has succeeded are the files
// written, each under a temporary name in the target folder (StagedFile),
// and only when all of them are written are they renamed into place:
// companions (.bin, .mtl) first and the main file last, so the main file
// never refers to a missing companion and no file is ever partial.
#include "io/assimp_scene.hpp"

#include <assimp/material.h>
#include <assimp/scene.h>
#include <unistd.h>

#include <algorithm>
#include <assimp/Exporter.hpp>
#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <cctype>
#include <cstring>
#include <memory>
#include <numeric>
#include <utility>

#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "core/atomic_file.hpp"

namespace ashlar {
namespace {

struct ExportFormat {
  const char* extension;  // lower case, without the dot
  const char* assimp_id;
  bool y_up;
};

constexpr ExportFormat kFormats[] = {
    {"glb", "glb2", true},   {"gltf", "gltf2", true}, {"obj", "obj", false},
    {"ply", "plyb", false},  {"stl", "stlb", false},
};

std::string extensions_list() {
  std::string list;
  for (const auto& extension : export_extensions()) list += (list.empty() ? "" : ", ") + extension;
  return list;
}

const ExportFormat& format_for(const std::string& path, const std::string& caller) {
  const std::string extension = file_extension(path);
  for (const ExportFormat& format : kFormats) {
    if (extension == format.extension) return format;
  }
  throw InvalidArgument(caller + ": cannot tell the format of '" + path +
                        "' from its extension; use one of: " + extensions_list());
}

// ---------------------------------------------------------------------------
// Scene building

aiVector3D to_ai(const Vec3& v, bool y_up) {
  return y_up ? aiVector3D(static_cast<ai_real>(v.x()), static_cast<ai_real>(v.z()),
                           static_cast<ai_real>(-v.y()))
              : aiVector3D(static_cast<ai_real>(v.x()), static_cast<ai_real>(v.y()),
                           static_cast<ai_real>(v.z()));
}

aiMesh* to_ai_mesh(const FlatMesh& flat, const std::string& name, unsigned material, bool y_up) {
  auto mesh = std::make_unique<aiMesh>();
  mesh->mName = aiString(name);
  mesh->mMaterialIndex = material;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = static_cast<unsigned>(flat.positions.size());
  mesh->mVertices = new aiVector3D[mesh->mNumVertices];
  mesh->mNormals = new aiVector3D[mesh->mNumVertices];
  for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
    mesh->mVertices[v] = to_ai(flat.positions[v], y_up);
    mesh->mNormals[v] = to_ai(flat.normals[v], y_up);
  }
  if (!flat.colors.empty()) {
    mesh->mColors[0] = new aiColor4D[mesh->mNumVertices];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const Rgb& c = flat.colors.at(v);
      mesh->mColors[0][v] = aiColor4D(static_cast<ai_real>(c.r), static_cast<ai_real>(c.g),
                                      static_cast<ai_real>(c.b), 1);
    }
  }
  mesh->mNumFaces = static_cast<unsigned>(flat.triangles.size());
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    aiFace& face = mesh->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    std::copy(flat.triangles[f].begin(), flat.triangles[f].end(), face.mIndices);
  }
  return mesh.release();
}

aiMaterial* make_material(const std::string& name, const Rgb& rgb, double opacity,
                          bool two_sided) {
  auto material = std::make_unique<aiMaterial>();
  const aiString material_name(name);
  material->AddProperty(&material_name, AI_MATKEY_NAME);
  const aiColor4D color(static_cast<ai_real>(rgb.r), static_cast<ai_real>(rgb.g),
                        static_cast<ai_real>(rgb.b), 1);
  material->AddProperty(&color, 1, AI_MATKEY_COLOR_DIFFUSE);
  material->AddProperty(&color, 1, AI_MATKEY_BASE_COLOR);
  // Stone: not metallic, rough.
  const ai_real metallic = 0, roughness = 0.9f;
  material->AddProperty(&metallic, 1, AI_MATKEY_METALLIC_FACTOR);
  material->AddProperty(&roughness, 1, AI_MATKEY_ROUGHNESS_FACTOR);
  const int two_sided_flag = two_sided ? 1 : 0;
  material->AddProperty(&two_sided_flag, 1, AI_MATKEY_TWOSIDED);
  // The glTF writer turns opacity below 1 into alpha blending.
  const ai_real alpha = static_cast<ai_real>(opacity);
  material->AddProperty(&alpha, 1, AI_MATKEY_OPACITY);
  return material.release();
}

// ---------------------------------------------------------------------------
// Buffered, all-or-nothing file output for assimp

// Files assimp finished writing, in the order it closed them.
struct PendingFiles {
  std::vector<std::pair<std::string, std::string>> files;
};

class MemoryStream : public Assimp::IOStream {
public:
  MemoryStream(std::string path, std::shared_ptr<PendingFiles> pending)
      : path_(std::move(path)), pending_(std::move(pending)) {}
  // Assimp sometimes deletes streams without IOSystem::Close, so the
  // destructor is where a file counts as finished.
  ~MemoryStream() override { pending_->files.emplace_back(path_, std::move(data_)); }

  size_t Read(void*, size_t, size_t) override { return 0; }
  size_t Write(const void* buffer, size_t size, size_t count) override {
    const size_t bytes = size * count;
    if (position_ + bytes > data_.size()) data_.resize(position_ + bytes);
    std::memcpy(&data_[position_], buffer, bytes);
    position_ += bytes;
    return count;
  }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    const size_t base = origin == aiOrigin_SET ? 0
                        : origin == aiOrigin_CUR ? position_
                                                 : data_.size();
    // Like a file, seeking past the end is allowed (the GLB writer skips its
    // header first); the gap reads as zeros once something is written.
    position_ = base + offset;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return position_; }
  size_t FileSize() const override { return data_.size(); }
  void Flush() override {}

private:
  std::string path_;
  std::shared_ptr<PendingFiles> pending_;
  std::string data_;
  size_t position_ = 0;
};

// Owned (and deleted) by the Exporter; PendingFiles outlives it.
class MemoryIOSystem : public Assimp::IOSystem {
public:
  explicit MemoryIOSystem(std::shared_ptr<PendingFiles> pending) : pending_(std::move(pending)) {}

  bool Exists(const char* path) const override {
    for (const auto& file : pending_->files) {
      if (file.first == path) return true;
    }
    return ::access(path, F_OK) == 0;
  }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* path, const char* mode) override {
    // Exporters only write; reading back is not offered.
    if (std::strchr(mode, 'w') == nullptr) return nullptr;
    return new MemoryStream(path, pending_);
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

private:
  std::shared_ptr<PendingFiles> pending_;
};

void commit(const PendingFiles& pending, const std::string& main_path) {
  const auto main_file = std::find_if(pending.files.begin(), pending.files.end(),
                                      [&](const auto& file) { return file.first == main_path; });
  if (main_file == pending.files.end()) {
    throw IoError("cannot export '" + main_path + "': the exporter wrote nothing");
  }
  std::vector<StagedFile> staged;
  for (const auto& [path, data] : pending.files) {
    if (path != main_path) staged.emplace_back(path, data);
  }
  staged.emplace_back(main_path, main_file->second);
  for (StagedFile& file : staged) file.commit();
}

}  // namespace

// Meshes, materials and nodes until write() hands them to an aiScene, which
// owns and frees them.
struct SceneWriter::Scene {
  std::vector<aiMesh*> meshes;
  std::vector<aiMaterial*> materials;
  std::vector<aiNode*> nodes;

  ~Scene() {
    for (aiMesh* mesh : meshes) delete mesh;
    for (aiMaterial* material : materials) delete material;
    for (aiNode* node : nodes) delete node;
  }
};

SceneWriter::SceneWriter(std::string path, const std::string& caller) : path_(std::move(path)) {
  const ExportFormat& format = format_for(path_, caller);
  y_up_ = format.y_up;
  assimp_id_ = format.assimp_id;
  scene_ = std::make_unique<Scene>();
}

SceneWriter::~SceneWriter() = default;

void SceneWriter::add_object(const std::string& name, const FlatMesh& mesh, const Rgb& color,
                             bool two_sided, double opacity) {
  const auto index = static_cast<unsigned>(scene_->meshes.size());
  scene_->materials.push_back(make_material(name, color, opacity * color.a, two_sided));
  scene_->meshes.push_back(to_ai_mesh(mesh, name, index, y_up_));
  auto node = std::make_unique<aiNode>(name);
  node->mNumMeshes = 1;
  node->mMeshes = new unsigned[1]{index};
  scene_->nodes.push_back(node.release());
}

void SceneWriter::write(const std::string& root_name) {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode(root_name);
  scene->mRootNode->addChildren(static_cast<unsigned>(scene_->nodes.size()),
                                scene_->nodes.data());
  scene_->nodes.clear();
  scene->mNumMeshes = static_cast<unsigned>(scene_->meshes.size());
  scene->mMeshes = new aiMesh*[scene_->meshes.size()];
  std::copy(scene_->meshes.begin(), scene_->meshes.end(), scene->mMeshes);
  scene_->meshes.clear();
  scene->mNumMaterials = static_cast<unsigned>(scene_->materials.size());
  scene->mMaterials = new aiMaterial*[scene_->materials.size()];
  std::copy(scene_->materials.begin(), scene_->materials.end(), scene->mMaterials);
  scene_->materials.clear();

  auto pending = std::make_shared<PendingFiles>();
  Assimp::Exporter exporter;
  exporter.SetIOHandler(new MemoryIOSystem(pending));
  if (exporter.Export(scene.get(), assimp_id_, path_) != AI_SUCCESS) {
    throw IoError("cannot export '" + path_ + "': " + exporter.GetErrorString());
  }
  commit(*pending, path_);
}

std::string file_extension(const std::string& path) {
  const auto slash = path.find_last_of('/');
  const auto dot = path.find_last_of('.');
  std::string extension;
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash)) {
    extension = path.substr(dot + 1);
  }
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

bool is_y_up_file(const std::string& path) {
  const std::string extension = file_extension(path);
  for (const ExportFormat& format : kFormats) {
    if (extension == format.extension) return format.y_up;
  }
  return false;
}

const std::vector<std::string>& export_extensions() {
  static const std::vector<std::string> extensions = [] {
    std::vector<std::string> result;
    for (const ExportFormat& format : kFormats) result.push_back(std::string(".") + format.extension);
    return result;
  }();
  return extensions;
}

}  // namespace ashlar
