// Mesh files through assimp: import objects as blocks, export structures.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "geometry/block.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct ImportOptions {
  double density = kDefaultDensity;  // kg/m^3 for every imported block
  // Vertices closer than this fraction of the scene's bounding-box diagonal
  // are welded (files such as STL repeat each vertex per triangle).
  double relative_weld_tolerance = 1e-9;
};

struct ImportedBlock {
  std::string name;  // node name, made unique ("name#2") when repeated
  Block block;
};

// Every node that carries meshes becomes one block (its meshes joined, in
// world coordinates). Throws IoError for unreadable files and GeometryError
// naming the object when a mesh is not a closed solid.
std::vector<ImportedBlock> import_blocks(const std::string& path, const ImportOptions& options);

struct Rgb {
  double r = 0.8, g = 0.8, b = 0.8;  // each in [0, 1]
};

struct ExportOptions {
  // One colour per block (size() == structure.size()), or empty for the
  // default grey.
  std::vector<Rgb> block_colors;
  bool interfaces = false;  // also write each contact polygon as a node
  Rgb interface_color{0.9, 0.2, 0.1};
  ContactOptions contact;
};

// Format from the extension: .glb, .gltf (glTF 2.0), .obj, .ply, .stl.
// Each block is a node named after it; every file is written atomically.
// Throws InvalidArgument for an unknown extension, IoError on failure.
void export_structure(const Structure& structure, const std::string& path,
                      const ExportOptions& options);

// Names of the supported export extensions, for error messages.
const std::vector<std::string>& export_extensions();

}  // namespace ashlar
