// An exported .gltf with its .bin, read back node by node, for the export
// tests.
#pragma once

#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "core/atomic_file.hpp"
#include "test_support.hpp"

struct GltfFile {
  nlohmann::json json;
  std::string bin;

  GltfFile(const TempDir& dir, const std::string& name)
      : json(nlohmann::json::parse(ashlar::read_file(dir.file(name)))),
        bin(ashlar::read_file(dir.file(json["buffers"][0]["uri"].get<std::string>()))) {}

  bool has_node(const std::string& node_name) const {
    for (const auto& node : json["nodes"]) {
      if (node.value("name", "") == node_name) return true;
    }
    return false;
  }
  const nlohmann::json& primitive(const std::string& node_name) const {
    for (const auto& node : json["nodes"]) {
      if (node.value("name", "") == node_name) {
        return json["meshes"][node["mesh"].get<int>()]["primitives"][0];
      }
    }
    throw std::runtime_error("no node " + node_name);
  }
  const nlohmann::json& accessor(const nlohmann::json& index) const {
    return json["accessors"][index.get<int>()];
  }
  int count(const std::string& node_name, const char* attribute) const {
    return accessor(primitive(node_name)["attributes"][attribute])["count"];
  }
  int triangles(const std::string& node_name) const {
    return accessor(primitive(node_name)["indices"])["count"].get<int>() / 3;
  }
  const nlohmann::json& base_color(const std::string& node_name) const {
    return json["materials"][primitive(node_name)["material"].get<int>()]["pbrMetallicRoughness"]
               ["baseColorFactor"];
  }
  // Vertex positions in ashlar's axes (glTF's y is ashlar's z).
  std::vector<ashlar::Vec3> positions(const std::string& node_name) const {
    const auto& positions = accessor(primitive(node_name)["attributes"]["POSITION"]);
    const auto& view = json["bufferViews"][positions["bufferView"].get<int>()];
    const char* data = bin.data() + view.value("byteOffset", 0) + positions.value("byteOffset", 0);
    std::vector<ashlar::Vec3> points;
    for (int k = 0; k < positions["count"].get<int>(); ++k) {
      float xyz[3];
      std::memcpy(xyz, data + sizeof xyz * k, sizeof xyz);
      points.emplace_back(xyz[0], -xyz[2], xyz[1]);
    }
    return points;
  }
};
