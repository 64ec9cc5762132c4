// FEA results as a VTK unstructured grid (vtu_file.hpp) and as deformed 3D
// meshes through assimp (assimp_scene.hpp).
#include "io/fea_export.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "io/assimp_scene.hpp"
#include "core/atomic_file.hpp"
#include "io/color_map.hpp"
#include "io/mesh_io.hpp"
#include "io/vtu_file.hpp"

namespace ashlar {
namespace {

constexpr int kVtkHexahedron = 12;
constexpr int kVtkPolyhedron = 42;
constexpr double kAutoScaleFraction = 0.05;  // of the bounding-box diagonal
// Octahedron radius, of the shortest element edge: neighbouring nodes' glyphs stay apart.
constexpr double kGlyphFraction = 0.25;
constexpr double kUndeformedOpacity = 0.3;

const Rgb kBlockGrey{0.8, 0.8, 0.8};
const Rgb kSupportGrey{0.5, 0.5, 0.5};
const Rgb kUndeformedGrey{0.6, 0.6, 0.6};
// glTF multiplies vertex colours by the material colour.
const Rgb kWhite{1.0, 1.0, 1.0};
const Rgb kTensionRed{0.9, 0.1, 0.1};
const Rgb kReleasedOrange{1.0, 0.55, 0.0};

// The checks both exports need: mesh and result belong to this structure,
// so every index used below is in range.
void check_mesh_and_result(const Structure& structure, const FeaMesh& mesh, const FeaResult& result,
                           const std::string& caller) {
  const size_t nodes = mesh.nodes().size(), elements = mesh.elements().size();
  const std::string advice = "; export a result with the mesh and structure it was computed on";
  if (result.displacements.size() != nodes) {
    throw InvalidArgument(
        caller + ": the result has " + std::to_string(result.displacements.size()) +
        " displacements but the mesh " + std::to_string(nodes) + " nodes" + advice);
  }
  if (!result.stresses.empty() && result.stresses.size() != elements) {
    throw InvalidArgument(caller + ": the result has " + std::to_string(result.stresses.size()) +
                          " stresses but the mesh " + std::to_string(elements) + " elements" +
                          advice);
  }
  std::vector<int> node_count(structure.size()), element_count(structure.size());
  auto count = [&](int block, std::vector<int>& counts) {
    if (block < 0 || block >= structure.size() || structure.is_support(block)) {
      throw InvalidArgument(caller + ": the mesh has a block " + std::to_string(block + 1) +
                            " that is not a free block of this structure" + advice);
    }
    ++counts[block];
  };
  for (size_t n = 0; n < nodes; ++n) count(mesh.node_block(static_cast<int>(n)), node_count);
  for (size_t e = 0; e < elements; ++e)
    count(mesh.element_block(static_cast<int>(e)), element_count);
  for (int b = 0; b < structure.size(); ++b) {
    if (structure.is_support(b)) continue;
    // Only a block with nodes is sure to be within the mesh's own block count.
    bool whole = node_count[b] > 0;
    if (whole) {
      const std::array<int, 3>& d = mesh.divisions(b);
      whole = node_count[b] == (d[0] + 1) * (d[1] + 1) * (d[2] + 1) &&
              element_count[b] == d[0] * d[1] * d[2];
    }
    if (!whole) {
      throw InvalidArgument(caller + ": the mesh does not mesh " + structure.label(b) +
                            advice);
    }
  }
  for (size_t n = 0; n < nodes; ++n) {
    if (!result.displacements[n].allFinite()) {
      throw InvalidArgument(caller + ": the displacement of node " + std::to_string(n + 1) +
                            " is not finite");
    }
  }
  for (size_t e = 0; e < result.stresses.size(); ++e) {
    if (!result.stresses[e].allFinite()) {
      throw InvalidArgument(caller + ": the stress of element " + std::to_string(e + 1) +
                            " is not finite");
    }
  }
  for (size_t c = 0; c < result.contacts.size(); ++c) {
    const int node = result.contacts[c].node;
    if (node < 0 || static_cast<size_t>(node) >= nodes) {
      throw InvalidArgument(caller + ": contact " + std::to_string(c + 1) + " is at node " +
                            std::to_string(node + 1) + ", not one of the mesh's " +
                            std::to_string(nodes) + advice);
    }
  }
}

// ---------------------------------------------------------------------------
// VTU

// Per-node sums over the contacts at each node.
struct NodeContacts {
  std::vector<Vec3> force;           // N, on the node's block
  std::vector<double> normal_force;  // N, compression positive
  std::vector<int> released;         // 0 or 1
};

NodeContacts node_contacts(const FeaMesh& mesh, const FeaResult& result,
                           const std::vector<Interface>& interfaces, const std::string& caller) {
  const size_t nodes = mesh.nodes().size();
  NodeContacts sums{std::vector<Vec3>(nodes, Vec3::Zero()), std::vector<double>(nodes, 0.0),
                    std::vector<int>(nodes, 0)};
  for (size_t c = 0; c < result.contacts.size(); ++c) {
    const FeaContact& contact = result.contacts[c];
    if (contact.interface < 0 || static_cast<size_t>(contact.interface) >= interfaces.size()) {
      throw InvalidArgument(caller + ": contact " + std::to_string(c + 1) + " is on interface " +
                            std::to_string(contact.interface + 1) + " of " +
                            std::to_string(interfaces.size()) +
                            "; pass structure.interfaces() with the analysis's contact options");
    }
    const Interface& joined = interfaces[contact.interface];
    const int block = mesh.node_block(contact.node);
    if (block != joined.a && block != joined.b) {
      throw InvalidArgument(
          caller + ": contact " + std::to_string(c + 1) + " is at a node of block " +
          std::to_string(block + 1) + ", which interface " + std::to_string(contact.interface + 1) +
          " does not join" + "; pass structure.interfaces() with the analysis's contact options");
    }
    sums.force[contact.node] += block == joined.b ? contact.force_on_b : Vec3(-contact.force_on_b);
    sums.normal_force[contact.node] += contact.normal_force;
    if (contact.released) sums.released[contact.node] = 1;
  }
  return sums;
}

void append_vec3(std::vector<double>& values, const Vec3& v) {
  values.insert(values.end(), {v.x(), v.y(), v.z()});
}

// Support blocks as cells: a hexahedron (8 corners joined like a cube's,
// not folded) as VTK_HEXAHEDRON, any other block as VTK_POLYHEDRON with its
// faces (outward, as Block keeps them).
struct SupportCells {
  std::vector<Vec3> points;
  std::vector<int> point_block, cell_block;
  std::vector<std::int64_t> connectivity, offsets, types;
  std::vector<std::int64_t> faces, face_offsets;  // face_offsets -1 for non-polyhedra
  bool polyhedra = false;
};

SupportCells support_cells(const Structure& structure, std::int64_t first_point,
                           std::int64_t first_connectivity) {
  SupportCells cells;
  for (int b = 0; b < structure.size(); ++b) {
    if (!structure.is_support(b)) continue;
    const Block& block = structure.block(b);
    const auto base = static_cast<std::int64_t>(first_point + cells.points.size());
    std::optional<HexNodes> corners;
    try {
      corners = hexahedron_corners(block, structure.label(b));
      if (!(hex_min_jacobian(*corners) > 0)) corners.reset();
    } catch (const InvalidArgument&) {
      // Not a hexahedron: written as a polyhedron below.
    }
    if (corners) {
      for (int a = 0; a < 8; ++a) {
        cells.points.push_back((*corners)[a]);
        cells.connectivity.push_back(base + a);
      }
      cells.types.push_back(kVtkHexahedron);
      cells.face_offsets.push_back(-1);
    } else {
      const std::vector<Vec3>& vertices = block.vertices();
      for (size_t v = 0; v < vertices.size(); ++v) {
        cells.points.push_back(vertices[v]);
        cells.connectivity.push_back(base + static_cast<std::int64_t>(v));
      }
      cells.types.push_back(kVtkPolyhedron);
      cells.faces.push_back(static_cast<std::int64_t>(block.faces().size()));
      for (const FaceLoop& face : block.faces()) {
        cells.faces.push_back(static_cast<std::int64_t>(face.size()));
        for (int v : face) cells.faces.push_back(base + v);
      }
      cells.face_offsets.push_back(static_cast<std::int64_t>(cells.faces.size()));
      cells.polyhedra = true;
    }
    cells.point_block.resize(cells.points.size(), b);
    cells.cell_block.push_back(b);
    cells.offsets.push_back(first_connectivity + static_cast<std::int64_t>(cells.connectivity.size()));
  }
  return cells;
}

// Stress holds xx yy zz yz xz xy; VTK's symmetric tensors are xx yy zz xy yz xz.
constexpr std::array<int, 6> kVtkTensorOrder = {0, 1, 2, 5, 3, 4};
const char* const kTensorComponentNames =
    " ComponentName0=\"XX\" ComponentName1=\"YY\" ComponentName2=\"ZZ\""
    " ComponentName3=\"XY\" ComponentName4=\"YZ\" ComponentName5=\"XZ\"";

void append_stress(std::vector<double>& values, const Stress& stress) {
  for (int k : kVtkTensorOrder) values.push_back(stress(k));
}

// The grid as written: the mesh's nodes and elements first (point n is node
// n, cell e element e), then each support block's corners and cell.
VtuGrid vtu_grid(const Structure& structure, const FeaMesh& mesh, const FeaResult& result,
                 const NodeContacts& contacts) {
  const auto& nodes = mesh.nodes();
  const auto& elements = mesh.elements();
  const size_t node_count = nodes.size(), element_count = elements.size();
  const SupportCells supports = support_cells(structure, static_cast<std::int64_t>(node_count),
                                              8 * static_cast<std::int64_t>(element_count));
  VtuGrid grid;
  grid.points = node_count + supports.points.size();
  grid.cells = element_count + supports.types.size();
  const bool stresses = !result.stresses.empty();

  // Point data; support points neither move nor touch a contact.
  std::vector<double> displacement, contact_force, normal_force;
  std::vector<std::int64_t> released, point_block;
  for (size_t n = 0; n < node_count; ++n) {
    append_vec3(displacement, result.displacements[n]);
    append_vec3(contact_force, contacts.force[n]);
    normal_force.push_back(contacts.normal_force[n]);
    released.push_back(contacts.released[n]);
    point_block.push_back(mesh.node_block(static_cast<int>(n)) + 1);
  }
  displacement.resize(3 * grid.points, 0.0);
  contact_force.resize(3 * grid.points, 0.0);
  normal_force.resize(grid.points, 0.0);
  released.resize(grid.points, 0);
  for (int b : supports.point_block) point_block.push_back(b + 1);
  grid.point_attributes = " Vectors=\"displacement\" Scalars=\"contact_normal_force\"";
  grid.point_data.push_back(real_array("displacement", 3, std::move(displacement)));
  grid.point_data.push_back(real_array("contact_force", 3, std::move(contact_force)));
  grid.point_data.push_back(real_array("contact_normal_force", 1, std::move(normal_force)));
  grid.point_data.push_back(integer_array("released", VtuType::Int32, std::move(released)));
  grid.point_data.push_back(integer_array("block", VtuType::Int32, std::move(point_block)));
  if (stresses) {
    // Each node's mean of the stresses of the elements around it; blocks
    // keep their own nodes, so the mean stays within the node's block.
    std::vector<Stress> sum(node_count, Stress::Zero());
    std::vector<int> count(node_count, 0);
    for (size_t e = 0; e < element_count; ++e) {
      for (int node : elements[e]) {
        sum[node] += result.stresses[e];
        ++count[node];
      }
    }
    std::vector<double> nodal, nodal_mises;
    for (size_t n = 0; n < node_count; ++n) {
      const Stress mean = sum[n] / count[n];  // every node is a corner of an element of its block
      append_stress(nodal, mean);
      nodal_mises.push_back(von_mises(mean));
    }
    nodal.resize(6 * grid.points, 0.0);
    nodal_mises.resize(grid.points, 0.0);
    grid.point_attributes += " Tensors=\"nodal_stress\"";
    grid.point_data.push_back(real_array("nodal_stress", 6, std::move(nodal), kTensorComponentNames));
    grid.point_data.push_back(real_array("nodal_von_mises", 1, std::move(nodal_mises)));
  }

  // Cell data; supports are rigid ground, with no stress computed.
  std::vector<std::int64_t> cell_block, support;
  for (size_t e = 0; e < element_count; ++e)
    cell_block.push_back(mesh.element_block(static_cast<int>(e)) + 1);
  for (int b : supports.cell_block) cell_block.push_back(b + 1);
  support.assign(grid.cells, 0);
  std::fill(support.begin() + static_cast<std::ptrdiff_t>(element_count), support.end(), 1);
  grid.cell_attributes = stresses ? " Scalars=\"von_mises\" Tensors=\"stress\"" : " Scalars=\"block\"";
  grid.cell_data.push_back(integer_array("block", VtuType::Int32, std::move(cell_block)));
  grid.cell_data.push_back(integer_array("support", VtuType::Int32, std::move(support)));
  if (stresses) {
    std::vector<double> stress, mises;
    for (const Stress& s : result.stresses) {
      append_stress(stress, s);
      mises.push_back(von_mises(s));
    }
    stress.resize(6 * grid.cells, 0.0);
    mises.resize(grid.cells, 0.0);
    grid.cell_data.push_back(real_array("stress", 6, std::move(stress), kTensorComponentNames));
    grid.cell_data.push_back(real_array("von_mises", 1, std::move(mises)));
  }

  std::vector<double> xyz;
  xyz.reserve(3 * grid.points);
  for (const Vec3& p : nodes) append_vec3(xyz, p);
  for (const Vec3& p : supports.points) append_vec3(xyz, p);
  grid.coordinates = real_array("", 3, std::move(xyz));

  std::vector<std::int64_t> connectivity, offsets, types;
  connectivity.reserve(8 * element_count + supports.connectivity.size());
  for (const auto& element : elements) connectivity.insert(connectivity.end(), element.begin(), element.end());
  connectivity.insert(connectivity.end(), supports.connectivity.begin(), supports.connectivity.end());
  for (size_t e = 0; e < element_count; ++e) offsets.push_back(8 * static_cast<std::int64_t>(e + 1));
  offsets.insert(offsets.end(), supports.offsets.begin(), supports.offsets.end());
  types.assign(element_count, kVtkHexahedron);
  types.insert(types.end(), supports.types.begin(), supports.types.end());
  grid.cell_arrays.push_back(integer_array("connectivity", VtuType::Int64, std::move(connectivity)));
  grid.cell_arrays.push_back(integer_array("offsets", VtuType::Int64, std::move(offsets)));
  grid.cell_arrays.push_back(integer_array("types", VtuType::UInt8, std::move(types)));
  if (supports.polyhedra) {
    std::vector<std::int64_t> face_offsets(element_count, -1);
    face_offsets.insert(face_offsets.end(), supports.face_offsets.begin(), supports.face_offsets.end());
    grid.cell_arrays.push_back(integer_array("faces", VtuType::Int64, supports.faces));
    grid.cell_arrays.push_back(integer_array("faceoffsets", VtuType::Int64, std::move(face_offsets)));
  }
  return grid;
}

// ---------------------------------------------------------------------------
// Deformed meshes

void check_mesh_options(const FeaMeshExportOptions& options, const std::string& caller) {
  if (!(options.scale >= 0.0) || !std::isfinite(options.scale)) {
    throw InvalidArgument(caller + ": scale must be a finite number >= 0 (0: automatic)");
  }
  if (options.color != "displacement" && options.color != "block") {
    throw InvalidArgument(caller + ": unknown color '" + options.color + "' (allowed: 'displacement', 'block')");
  }
  check_color_map(options.map);
}

// The faces of a hexahedron as corner indices (hex_element.hpp order),
// counter-clockwise seen from outside, given a positive Jacobian, which
// FeaMesh ensures: zeta = -1, zeta = +1, eta = -1, xi = +1, eta = +1, xi = -1.
constexpr std::array<std::array<int, 4>, 6> kHexFaces = {
    {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};

// Per block, the element faces that no other element shares: the block's
// boundary surface, outward. Blocks keep their own nodes (fea_mesh.hpp), so
// a face is shared only within its block.
std::vector<std::vector<std::array<int, 4>>> boundary_quads(const FeaMesh& mesh, int blocks) {
  const auto& elements = mesh.elements();
  struct Face {
    std::array<int, 4> key;  // sorted nodes
    size_t index;            // element * 6 + side
  };
  std::vector<Face> faces;
  faces.reserve(6 * elements.size());
  for (size_t e = 0; e < elements.size(); ++e) {
    for (size_t side = 0; side < 6; ++side) {
      Face face{{}, 6 * e + side};
      for (int k = 0; k < 4; ++k) face.key[k] = elements[e][kHexFaces[side][k]];
      std::sort(face.key.begin(), face.key.end());
      faces.push_back(face);
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.key < y.key; });
  std::vector<bool> boundary(faces.size(), false);
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) boundary[faces[i].index] = true;
    i = j;
  }
  std::vector<std::vector<std::array<int, 4>>> quads(blocks);
  for (size_t index = 0; index < boundary.size(); ++index) {
    if (!boundary[index]) continue;
    const size_t e = index / 6, side = index % 6;
    std::array<int, 4> quad;
    for (int k = 0; k < 4; ++k) quad[k] = elements[e][kHexFaces[side][k]];
    quads[mesh.element_block(static_cast<int>(e))].push_back(quad);
  }
  return quads;
}

// An octahedron centred at `center`, its vertices `radius` away along the axes.
void add_octahedron(FlatMesh& mesh, const Vec3& center, double radius) {
  for (int octant = 0; octant < 8; ++octant) {
    const Vec3 sign((octant & 1) ? -1 : 1, (octant & 2) ? -1 : 1, (octant & 4) ? -1 : 1);
    std::vector<Vec3> loop = {center + radius * sign.x() * Vec3::UnitX(),
                              center + radius * sign.y() * Vec3::UnitY(),
                              center + radius * sign.z() * Vec3::UnitZ()};
    // x, y, z runs counter-clockwise about (1, 1, 1); each mirror reverses it.
    if (sign.prod() < 0) std::swap(loop[1], loop[2]);
    mesh.add_polygon(loop, sign.normalized(), false);
  }
}

double automatic_scale(const Structure& structure, const FeaResult& result) {
  double largest = 0.0;
  for (const Vec3& u : result.displacements) largest = std::max(largest, u.norm());
  return largest > 0.0 ? kAutoScaleFraction * structure.bounds().diagonal() / largest : 0.0;
}

std::vector<Rgb> displacement_colors(const FeaResult& result, const std::string& map) {
  std::vector<double> magnitudes;
  magnitudes.reserve(result.displacements.size());
  for (const Vec3& u : result.displacements) magnitudes.push_back(u.norm());
  const double largest =
      magnitudes.empty() ? 0.0 : *std::max_element(magnitudes.begin(), magnitudes.end());
  // Nothing moved: every vertex gets the colour of zero.
  return map_colors(magnitudes, 0.0, largest > 0.0 ? largest : 1.0, map);
}

// The shortest element edge of a block, estimated from the block's mean
// edge length along each parametric direction and its divisions (m).
double shortest_element_edge(const FeaMesh& mesh, int block) {
  constexpr int kEdges[3][4][2] = {{{0, 1}, {3, 2}, {4, 5}, {7, 6}},
                                   {{0, 3}, {1, 2}, {4, 7}, {5, 6}},
                                   {{0, 4}, {1, 5}, {2, 6}, {3, 7}}};
  const HexNodes& corners = mesh.corners(block);
  double shortest = std::numeric_limits<double>::infinity();
  for (int d = 0; d < 3; ++d) {
    double length = 0.0;
    for (const auto& edge : kEdges[d]) length += (corners[edge[1]] - corners[edge[0]]).norm() / 4;
    shortest = std::min(shortest, length / mesh.divisions(block)[d]);
  }
  return shortest;
}

void add_contact_glyphs(const FeaMesh& mesh, const FeaResult& result,
                        const std::vector<Vec3>& drawn, SceneWriter& writer) {
  // The analysis's own judgement of tension (FeaSettings::tension_tolerance),
  // so that round-off on a node that carries nothing is not drawn as tension.
  std::vector<bool> tension(drawn.size(), false), released(drawn.size(), false);
  for (const FeaContact& contact : result.contacts) {
    if (contact.released) {
      released[contact.node] = true;
    } else if (contact.tensile) {
      tension[contact.node] = true;
    }
  }
  auto glyphs = [&](const std::vector<bool>& marked) {
    FlatMesh glyph_mesh;
    for (size_t n = 0; n < marked.size(); ++n) {
      if (!marked[n]) continue;
      const int block = mesh.node_block(static_cast<int>(n));
      add_octahedron(glyph_mesh, drawn[n], kGlyphFraction * shortest_element_edge(mesh, block));
    }
    return glyph_mesh;
  };
  const FlatMesh tension_mesh = glyphs(tension), released_mesh = glyphs(released);
  if (!tension_mesh.positions.empty()) {
    writer.add_object("tension nodes", tension_mesh, kTensionRed, false);
  }
  if (!released_mesh.positions.empty()) {
    writer.add_object("released nodes", released_mesh, kReleasedOrange, false);
  }
}

}  // namespace

void export_fea_vtu(const Structure& structure, const FeaMesh& mesh, const FeaResult& result,
                    const std::vector<Interface>& interfaces, const std::string& path,
                    const FeaVtuOptions& options) {
  const std::string caller = "export_fea_vtu";
  if (file_extension(path) != "vtu") {
    throw InvalidArgument(caller + ": '" + path +
                          "' does not end in .vtu (VTK readers choose the format by extension)");
  }
  check_mesh_and_result(structure, mesh, result, caller);
  const NodeContacts contacts = node_contacts(mesh, result, interfaces, caller);
  write_file_atomically(path, vtu_text(vtu_grid(structure, mesh, result, contacts), options.format));
}

void export_fea_mesh(const Structure& structure, const FeaMesh& mesh, const FeaResult& result,
                     const std::string& path, const FeaMeshExportOptions& options) {
  const std::string caller = "export_fea_mesh";
  SceneWriter writer(path, caller);
  check_mesh_options(options, caller);
  check_mesh_and_result(structure, mesh, result, caller);

  const double scale = options.scale > 0.0 ? options.scale : automatic_scale(structure, result);
  std::vector<Vec3> drawn(mesh.nodes().size());
  for (size_t n = 0; n < drawn.size(); ++n)
    drawn[n] = mesh.nodes()[n] + scale * result.displacements[n];
  const bool by_displacement = options.color == "displacement";
  const std::vector<Rgb> colors =
      by_displacement ? displacement_colors(result, options.map) : std::vector<Rgb>{};
  const auto quads = boundary_quads(mesh, structure.size());

  for (int b = 0; b < structure.size(); ++b) {
    if (structure.is_support(b)) {
      writer.add_object(structure.name(b), block_mesh(structure.block(b)), kSupportGrey, false);
      continue;
    }
    FlatMesh surface;
    for (const std::array<int, 4>& quad : quads[b]) {
      const auto base = static_cast<unsigned>(surface.positions.size());
      const std::vector<Vec3> loop = {drawn[quad[0]], drawn[quad[1]], drawn[quad[2]],
                                      drawn[quad[3]]};
      // Deformed quadrilaterals need not be planar; Newell's normal is their mean plane's.
      const Vec3 normal = newell_normal(loop).normalized();
      for (int k = 0; k < 4; ++k) {
        surface.positions.push_back(loop[k]);
        surface.normals.push_back(normal);
        if (by_displacement) surface.colors.push_back(colors[quad[k]]);
      }
      surface.triangles.push_back({base, base + 1, base + 2});
      surface.triangles.push_back({base, base + 2, base + 3});
    }
    writer.add_object(structure.name(b), surface, by_displacement ? kWhite : kBlockGrey, false);
  }
  if (options.undeformed) {
    for (int b = 0; b < structure.size(); ++b) {
      if (structure.is_support(b)) continue;
      writer.add_object(structure.name(b) + " (undeformed)", block_mesh(structure.block(b)),
                        kUndeformedGrey, false, kUndeformedOpacity);
    }
  }
  if (options.contacts) add_contact_glyphs(mesh, result, drawn, writer);
  writer.write("ashlar fea");
}

}  // namespace ashlar
