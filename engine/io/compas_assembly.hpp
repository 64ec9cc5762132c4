// COMPAS Assembly JSON: the block assemblies of compas_assembly, which
// compas_rbe and compas_cra analyse and the COMPAS viewers draw.
//
// Read: the data layouts of compas 2.x ({"dtype", "data"} objects: an
// Assembly whose graph's nodes carry a Block mesh and is_support, and whose
// edges carry a list of Interfaces with points, frame and forces), compas 1.x
// (the same with {"dtype", "value"}) and compas_assembly 0.x ({"assembly":
// network with interface_points / interface_uvw on its edges, "blocks":
// meshes by node key}); a plain list of meshes gives blocks only.
// Written: the compas 2.x layout, with ashlar's vertex forces on each
// interface under compas_rbe's names.
//
// Conventions (those of compas_assembly and compas_rbe, and ashlar's): an
// edge (u, v) holds the interfaces between blocks u and v, each with a frame
// whose z axis (xaxis x yaxis) points from u into v; per interface point a
// force {c_np, c_nn, c_u, c_v} acts on v as (c_np - c_nn) z + c_u xaxis +
// c_v yaxis, and its opposite on u: c_np compression, c_nn tension, c_u and
// c_v friction along the frame's axes. Lengths in metres, forces in newtons.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/mesh_io.hpp"

namespace ashlar {

struct EquilibriumResult;

struct CompasAssembly {
  std::string layout;  // "compas 2", "compas 1", "compas_assembly 0.x" or "list of meshes"
  // In the file's node order; named by the mesh's own name, or "node <key>"
  // when it has none or only the class default ("Block", "Mesh").
  std::vector<ImportedBlock> blocks;
  std::vector<bool> supports;  // the nodes' is_support
  // The interfaces the file stores: between blocks a and b (0-based, the
  // edge's u and v), a polygon and the frame's normal (from a into b) when
  // it has a frame.
  struct StoredInterface {
    int a = -1, b = -1;
    std::vector<Vec3> points;
    std::optional<Vec3> normal;
    std::string where;  // "<path>: graph.edge.0.1.interfaces[0]", for messages
  };
  std::vector<StoredInterface> interfaces;
};

// Reads a COMPAS assembly (density, planarity and may_open as for meshes).
// Throws IoError naming the file and the entry at fault, and GeometryError
// naming the block when a mesh is not a valid block.
CompasAssembly read_compas_assembly(const std::string& path, const ImportOptions& options);

// The assembly as a structure: its blocks, supports where the file says so
// or `also_support` (may be empty) chooses, and with `stored_interfaces` the
// file's interfaces as explicit ones (Structure::add_interface); without,
// contacts are left to detection. Throws IoError naming the interface
// add_interface refuses.
Structure compas_structure(CompasAssembly assembly, bool stored_interfaces,
                           const std::function<bool(const ImportedBlock&)>& also_support);

struct CompasExportOptions {
  ContactOptions contact;  // the interfaces written: structure.interfaces(contact)
  // An analysis of this structure with these contact options: its vertex
  // forces are written on the interfaces (else forces are null). Not owned.
  const EquilibriumResult* result = nullptr;
};

// Writes the structure as a compas 2.x Assembly, atomically: one node per
// block (a Block mesh, is_support), one edge per pair of blocks in contact
// with its interfaces (points, size, frame, forces).
std::string compas_assembly_json(const Structure& structure, const CompasExportOptions& options);
void write_compas_assembly(const Structure& structure, const std::string& path,
                           const CompasExportOptions& options);

}  // namespace ashlar
