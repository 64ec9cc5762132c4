// The glTF 2.0 binary is written here rather than through assimp: assimp's
// glTF 2 exporter (5.2) makes one animation per animated node, which viewers
// play one at a time, so a collapse would show a single block moving.
// Layout: one buffer; per block a position, a normal and an index view;
// then the key times and, per free block, its translations and rotations.
#include "io/simulation_export.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <tuple>
#include <type_traits>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "io/assimp_scene.hpp"
#include "io/mesh_io.hpp"
#include "io/option_checks.hpp"

namespace ashlar {
namespace {

using json = nlohmann::json;

constexpr int kFloat = 5126, kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// glTF's +Y up from ashlar's +Z up.
Eigen::Vector3f y_up(const Vec3& v) { return Eigen::Vector3f(float(v.x()), float(v.z()), float(-v.y())); }

class GlbBuilder {
public:
  // Appends floats (or indices) as one buffer view and an accessor over it;
  // returns the accessor's index. `components` per element; min and max
  // are written when asked (positions and key times need them).
  template <class Scalar>
  int add(const std::vector<Scalar>& data, int components, const char* type, int target, bool bounds) {
    const size_t offset = bin_.size();
    bin_.resize(offset + data.size() * sizeof(Scalar));
    std::memcpy(&bin_[offset], data.data(), data.size() * sizeof(Scalar));
    json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size() * sizeof(Scalar)}};
    if (target) view["target"] = target;
    views_.push_back(view);
    json accessor = {{"bufferView", views_.size() - 1},
                     {"componentType", std::is_same<Scalar, float>::value ? kFloat : kUnsignedInt},
                     {"count", data.size() / components},
                     {"type", type}};
    if (bounds) {
      std::vector<double> lo(components, std::numeric_limits<double>::infinity()), hi(components, -lo[0]);
      for (size_t k = 0; k < data.size(); ++k) {
        lo[k % components] = std::min(lo[k % components], double(data[k]));
        hi[k % components] = std::max(hi[k % components], double(data[k]));
      }
      accessor["min"] = lo;
      accessor["max"] = hi;
    }
    accessors_.push_back(accessor);
    return static_cast<int>(accessors_.size() - 1);
  }

  // The .glb: header, JSON chunk (space padded), BIN chunk (zero padded).
  std::string file(json document) const {
    document["buffers"] = json::array({{{"byteLength", bin_.size()}}});
    document["bufferViews"] = views_;
    document["accessors"] = accessors_;
    std::string text = document.dump();
    text.resize((text.size() + 3) / 4 * 4, ' ');
    std::string bin = bin_;
    bin.resize((bin.size() + 3) / 4 * 4, '\0');
    std::string out;
    const auto word = [&](std::uint32_t value) { out.append(reinterpret_cast<const char*>(&value), 4); };
    word(0x46546C67);  // "glTF"
    word(2);
    word(static_cast<std::uint32_t>(12 + 8 + text.size() + 8 + bin.size()));
    word(static_cast<std::uint32_t>(text.size()));
    word(0x4E4F534A);  // "JSON"
    out += text;
    word(static_cast<std::uint32_t>(bin.size()));
    word(0x004E4942);  // "BIN"
    out += bin;
    return out;
  }

private:
  std::string bin_;
  json views_ = json::array(), accessors_ = json::array();
};

}  // namespace

void check_animation(const Structure& structure, const SimulationResult& result, double fps) {
  if (result.poses.empty() || result.poses.front().size() != static_cast<size_t>(structure.size())) {
    throw InvalidArgument("export: the simulation is of a structure with " +
                          std::to_string(result.poses.empty() ? 0 : result.poses.front().size()) +
                          " blocks, this one has " + std::to_string(structure.size()));
  }
  if (!(fps >= 0.0) || !std::isfinite(fps)) {
    throw InvalidArgument("export: fps must be a number of frames per second > 0 (0: the recorded frames), got " +
                          shortest_number(fps));
  }
}

AnimationFrames animation_frames(const SimulationResult& result, double fps) {
  AnimationFrames frames;
  const auto add = [&](double t, std::vector<RigidPose> at) {
    if (!frames.times.empty() && float(t) <= frames.times.back()) return;
    frames.times.push_back(float(t));
    frames.poses.push_back(std::move(at));
  };
  if (fps == 0.0) {
    for (size_t k = 0; k < result.times.size(); ++k) add(result.times[k], result.poses[k]);
    return frames;
  }
  const double end = result.times.back();
  for (long k = 0; k / fps < end; ++k) add(k / fps, poses_at(result, k / fps));
  add(end, result.poses.back());
  return frames;
}

void export_animation(const Structure& structure, const SimulationResult& result, const std::string& path,
                      const AnimationOptions& options) {
  if (file_extension(path) != "glb") {
    throw InvalidArgument("export: an animation is written as .glb or .html, got '" + path +
                          "' (give frame = k for a still in another format)");
  }
  check_animation(structure, result, options.fps);
  check_block_colors(structure, options.block_colors, "export");
  GlbBuilder glb;
  json nodes = json::array(), meshes = json::array(), materials = json::array();
  json children = json::array();
  for (int i = 0; i < structure.size(); ++i) {
    const Block& block = structure.block(i);
    const FlatMesh mesh = block_mesh(block);
    std::vector<float> positions, normals;
    std::vector<std::uint32_t> indices;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Eigen::Vector3f p = y_up(mesh.positions[v] - block.centroid());
      const Eigen::Vector3f n = y_up(mesh.normals[v]).normalized();
      positions.insert(positions.end(), {p.x(), p.y(), p.z()});
      normals.insert(normals.end(), {n.x(), n.y(), n.z()});
    }
    for (const auto& triangle : mesh.triangles) indices.insert(indices.end(), triangle.begin(), triangle.end());
    const int position = glb.add(positions, 3, "VEC3", kArrayBuffer, true);
    const int normal = glb.add(normals, 3, "VEC3", kArrayBuffer, false);
    const int index = glb.add(indices, 1, "SCALAR", kElementArrayBuffer, false);
    const Rgb color = options.block_colors.empty() ? Rgb{} : options.block_colors[i];
    json material = {{"name", structure.name(i)},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {color.r, color.g, color.b, color.a}},
                       {"metallicFactor", 0.0},
                       {"roughnessFactor", 0.9}}}};
    if (color.a < 1.0) material["alphaMode"] = "BLEND";
    materials.push_back(material);
    json primitive = {{"attributes", {{"POSITION", position}, {"NORMAL", normal}}}, {"indices", index}, {"material", i}};
    meshes.push_back({{"name", structure.name(i)}, {"primitives", json::array({primitive})}});
    const Eigen::Vector3f at = y_up(block.centroid());
    nodes.push_back({{"name", structure.name(i)}, {"mesh", i}, {"translation", {at.x(), at.y(), at.z()}}});
    children.push_back(i);
  }
  nodes.push_back({{"name", "ashlar simulation"}, {"children", children}});

  const AnimationFrames frames = animation_frames(result, options.fps);
  const int input = glb.add(frames.times, 1, "SCALAR", 0, true);
  json samplers = json::array(), channels = json::array();
  for (int i = 0; i < structure.size(); ++i) {
    if (structure.is_support(i)) continue;
    std::vector<float> translations, rotations;
    for (const std::vector<RigidPose>& frame : frames.poses) {
      const Eigen::Vector3f p = y_up(frame[i].position);
      const Quat& q = frame[i].rotation;
      const Eigen::Vector3f axis = y_up(q.vec());
      Eigen::Vector4f r(axis.x(), axis.y(), axis.z(), float(q.w()));
      r.normalize();
      translations.insert(translations.end(), {p.x(), p.y(), p.z()});
      rotations.insert(rotations.end(), {r.x(), r.y(), r.z(), r.w()});
    }
    for (const auto& [path_name, data, type] :
         {std::make_tuple("translation", &translations, "VEC3"), std::make_tuple("rotation", &rotations, "VEC4")}) {
      const int output = glb.add(*data, type[3] - '0', type, 0, false);
      samplers.push_back({{"input", input}, {"output", output}, {"interpolation", "LINEAR"}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", i}, {"path", path_name}}}});
    }
  }
  json document = {{"asset", {{"version", "2.0"}, {"generator", "ashlar simulation"}}},
                   {"scene", 0},
                   {"scenes", json::array({{{"nodes", json::array({structure.size()})}}})},
                   {"nodes", nodes},
                   {"meshes", meshes},
                   {"materials", materials}};
  if (!channels.empty()) {
    document["animations"] = json::array({{{"name", "simulation"}, {"samplers", samplers}, {"channels", channels}}});
  }
  write_file_atomically(path, glb.file(document));
}

}  // namespace ashlar
