// Export of a finite-element result (fea.hpp): the mesh with its fields as a
// VTK file for ParaView, and the deformed blocks as a 3D file.
#pragma once

#include <string>
#include <vector>

#include "fea/fea.hpp"
#include "fea/fea_mesh.hpp"
#include "structure/interface.hpp"
#include "structure/structure.hpp"
#include "io/vtu_file.hpp"

namespace ashlar {

struct FeaVtuOptions {
  // Binary files are about a fifth of the size of ASCII ones and take half
  // the time to write; ASCII is for reading by eye or by simple tools.
  VtuFormat format = VtuFormat::Binary;
};

// Writes mesh and result as a VTK XML UnstructuredGrid (file format
// version 1.0), for ParaView and other VTK readers. The grid is undeformed;
// ParaView's "Warp By Vector" on `displacement` draws the deformed shape.
//
// Binary (the default): zlib-compressed raw appended data, as VTK writes
// it; ASCII: every array inline (vtu_text, vtu_file.hpp).
//
// Inputs:
//   structure   the analysed structure (free blocks meshed by `mesh`)
//   mesh        #N nodes, #E elements
//   result      analyze_fea(structure, mesh, settings)
//   interfaces  structure.interfaces(settings.contact): FeaContact::interface
//               indexes it, and it tells which block of a contact is b
//   path        ending in .vtu (VTK readers pick the reader by extension)
//
// Points: the #N nodes first, node n is point n; then each support block's
// corners, supports in block order. Cells: the #E elements first, element e
// is cell e, type VTK_HEXAHEDRON (12); then one cell per support block in
// block order: VTK_HEXAHEDRON for a hexahedron (8 corners, 6 four-sided
// faces joined like a cube's, not folded), otherwise VTK_POLYHEDRON (42)
// with its faces (the <Cells> then also hold `faces` and `faceoffsets`,
// -1 for every other cell). Our hexahedron order (hex_element.hpp) is
// VTK's: 0-3 the base, right-handed about the direction to 4-7, each of 4-7
// above its base corner, so connectivity is each element's nodes as they
// are.
//
// Point data, one tuple per point; 0 on support points (the fixed ground)
// except `block`:
//   displacement          3 x Float64, m
//   contact_force         3 x Float64, N: the sum over the node's contacts of
//                         the force on the node's block (force_on_b when the
//                         block is the interface's b, else -force_on_b);
//                         0 away from contacts
//   contact_normal_force  Float64, N, the sum of the contacts' normal forces,
//                         compression positive
//   released              Int32, 1 when relaxation released a contact of the
//                         node, else 0
//   block                 Int32, 1-based block index
//   nodal_stress          6 x Float64, Pa, only when result.stresses is
//                         filled: the mean of the stresses of the elements
//                         that have the node as a corner (all within its
//                         block: blocks keep their own nodes); tensor order
//                         as `stress` below
//   nodal_von_mises       Float64, Pa, von_mises() of nodal_stress; with it
// Cell data, one tuple per cell; 0 on support cells except `block` and
// `support` (a support is rigid: no stress is computed in it):
//   block                 Int32, 1-based block index
//   support               Int32, 1 for a support block's cell, 0 for an element
//   stress                6 x Float64, Pa, at the element centre; only when
//                         result.stresses is filled. Components in VTK's
//                         symmetric-tensor order xx yy zz xy yz xz, which
//                         ParaView's tensor filters (principal stresses)
//                         assume: NOT the order of Stress (xx yy zz yz xz
//                         xy). Each component's name is in the file.
//   von_mises             Float64, Pa, von_mises() of the stress; with it
//
// Doubles are written exactly in both formats (ASCII with 17 significant
// digits). The file is written whole or not at all.
//
// Throws InvalidArgument when the path does not end in .vtu, when mesh,
// result or interfaces are not of this structure (counts or indices out of
// range, a node of a support block) or a displacement or stress is not
// finite; IoError when the file cannot be written.
void export_fea_vtu(const Structure& structure, const FeaMesh& mesh, const FeaResult& result,
                    const std::vector<Interface>& interfaces, const std::string& path,
                    const FeaVtuOptions& options = {});

struct FeaMeshExportOptions {
  // Displacement magnification: a node is drawn at position + scale *
  // displacement. 0: automatic, the largest displacement drawn as 5% of the
  // structure's bounding-box diagonal, since elastic displacements of
  // masonry are too small to see. Give a value to compare several exports.
  double scale = 0.0;
  // Also draw each free block undeformed, translucent grey, as a node
  // "<name> (undeformed)".
  bool undeformed = false;
  // "displacement": vertex colours by displacement magnitude, from 0 to the
  // largest in the result, through colour map `map`; "block": every block
  // one plain grey.
  std::string color = "displacement";
  std::string map = "viridis";  // one of color_map_names()
  // Contact nodes in tension (FeaContact::tensile: by the analysis's
  // tension_tolerance, so round-off is not drawn as tension) as small red
  // octahedra, node "tension nodes", and released ones as orange
  // octahedra, node "released nodes", at their drawn positions.
  bool contacts = true;
};

// Writes the deformed structure as a 3D file through assimp; the format
// comes from the extension (export_extensions(): .glb, .gltf, .obj, .ply,
// .stl), glTF rotated to +Y up as export_structure does.
//
// Each free block is a node named after it (structure.name) holding the
// boundary surface of its element grid: the element faces on each block
// face (refine x refine for a uniform mesh), each split into two triangles
// facing outwards, flat-shaded, at the drawn node positions. Supports are drawn undeformed in grey,
// named after them; they do not move. Single precision, as every assimp
// export.
//
// Throws InvalidArgument for an unknown extension, colour or colour map, a
// negative or non-finite scale, a mesh or result not of this structure, or
// a non-finite displacement; IoError when the file cannot be written (whole
// or not at all).
void export_fea_mesh(const Structure& structure, const FeaMesh& mesh, const FeaResult& result,
                     const std::string& path, const FeaMeshExportOptions& options = {});

}  // namespace ashlar
