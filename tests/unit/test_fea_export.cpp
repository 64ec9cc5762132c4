// Export of FEA results: the VTK unstructured grid and the deformed meshes.
// The results are made by hand (a known linear displacement field, chosen
// contacts and stresses), so these tests do not depend on the analysis.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <locale>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "fea/fea.hpp"
#include "fea/fea_mesh.hpp"
#include "fea/hex_element.hpp"
#include "geometry/block_builders.hpp"
#include "core/atomic_file.hpp"
#include "io/fea_export.hpp"
#include "io/mesh_io.hpp"
#include "gltf_file.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// A ground slab, a 1 m cube on it and a half-height cap on the cube.
Structure stacked_blocks() {
  Structure s;
  s.add(box({2, 2, 0.5}, {0, 0, -0.25}), true, "ground");
  s.add(box({1, 1, 1}, {0, 0, 0.5}), false, "cube");
  s.add(box({1, 1, 0.5}, {0, 0, 1.25}), false, "cap");
  return s;
}

// u(x) = A x + c: linear, so the deformed blocks are exact affine images of
// the undeformed ones. Values with many significant digits test precision.
const Mat3 kGradient =
    (Mat3() << 1e-4 / 3, 2e-5, 0, -3e-5, 5e-5 / 7, 1e-5, 0, 4e-5, -2e-4 / 9).finished();
const Vec3 kShift(1e-4 / 3, -2e-5 / 11, 7e-6);

Vec3 linear_field(const Vec3& x) { return kGradient * x + kShift; }

// The node of `block` at position p.
int node_at(const FeaMesh& mesh, int block, const Vec3& p) {
  for (size_t n = 0; n < mesh.nodes().size(); ++n) {
    if (mesh.node_block(static_cast<int>(n)) == block && (mesh.nodes()[n] - p).norm() < 1e-12) {
      return static_cast<int>(n);
    }
  }
  ADD_FAILURE() << "no node of block " << block << " at " << p.transpose();
  return -1;
}

struct HandMade {
  Structure structure = stacked_blocks();
  FeaMesh mesh{structure, 2};
  FeaResult result;
  // Contact nodes: cube bottom corner in compression, cap bottom corner in
  // tension, a released cube top corner, a cube top edge midpoint in
  // compression.
  int compressed = -1, tensile = -1, released = -1, cube_top = -1;

  HandMade() {
    const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces();
    const std::vector<Interface>& interfaces = *interfaces_list;
    EXPECT_EQ(interfaces.size(), 2u);  // ground-cube (a = 0, b = 1), cube-cap (a = 1, b = 2)
    for (const Vec3& x : mesh.nodes()) result.displacements.push_back(linear_field(x));
    for (size_t e = 0; e < mesh.elements().size(); ++e) {
      Stress stress;
      stress << 1.1e5, -2.2e5, 3.3e5, 4.4e4, -5.5e4, 6.6e4;
      result.stresses.push_back(stress * (1.0 + e / 3.0));
    }
    compressed = node_at(mesh, 1, {-0.5, -0.5, 0});
    tensile = node_at(mesh, 2, {0.5, 0.5, 1});
    released = node_at(mesh, 1, {-0.5, 0.5, 1});
    cube_top = node_at(mesh, 1, {0, -0.5, 1});
    auto contact = [&](int interface, int node, const Vec3& force_on_b, bool is_released) {
      FeaContact c;
      c.interface = interface;
      c.node = node;
      c.block = mesh.node_block(node);
      c.force_on_b = force_on_b;
      c.normal_force = force_on_b.dot(interfaces[interface].normal);
      c.tensile = c.normal_force < 0 && !is_released;
      c.released = is_released;
      c.released_at = is_released ? 1 : 0;
      result.contacts.push_back(c);
    };
    contact(0, compressed, {0, 0, 100}, false);
    contact(1, tensile, {1, 0, -5}, false);
    contact(1, released, Vec3::Zero(), true);
    contact(1, cube_top, {0, 2, 30}, false);
    result.total_weight = 1000;
    result.max_displacement = 0;
    for (const Vec3& u : result.displacements) {
      result.max_displacement = std::max(result.max_displacement, u.norm());
    }
  }
};

// ---------------------------------------------------------------------------
// VTU parsing, by plain string search

std::string section(const std::string& text, const std::string& tag) {
  const auto begin = text.find("<" + tag);
  const auto end = text.find("</" + tag + ">");
  if (begin == std::string::npos || end == std::string::npos) return {};
  return text.substr(begin, end - begin);
}

long attribute(const std::string& text, const std::string& name) {
  const auto at = text.find(name + "=\"");
  if (at == std::string::npos) return -1;
  return std::stol(text.substr(at + name.size() + 2));
}

// The opening tag of the DataArray `name` in `text` (empty name: the first).
std::string array_tag(const std::string& text, const std::string& name) {
  const auto at = name.empty() ? text.find("<DataArray") : text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const auto begin = text.rfind("<DataArray", at);
  return text.substr(begin, text.find('>', at) - begin);
}

std::vector<double> array_values(const std::string& text, const std::string& name) {
  const auto at = name.empty() ? text.find("<DataArray") : text.find("Name=\"" + name + "\"");
  if (at == std::string::npos) return {};
  const auto begin = text.find('>', at) + 1;
  std::istringstream in(text.substr(begin, text.find("</DataArray>", begin) - begin));
  in.imbue(std::locale::classic());
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

Vec3 tuple3(const std::vector<double>& values, int i) {
  return {values.at(3 * i), values.at(3 * i + 1), values.at(3 * i + 2)};
}

// ---------------------------------------------------------------------------
// Mesh file reading


// The vertex positions ("v x y z [r g b]") of an OBJ file.
std::vector<Vec3> obj_vertices(const std::string& path) {
  std::istringstream lines(read_file(path));
  lines.imbue(std::locale::classic());
  std::vector<Vec3> vertices;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream in(line.substr(2));
    in.imbue(std::locale::classic());
    double x, y, z;
    in >> x >> y >> z;
    vertices.emplace_back(x, y, z);
  }
  return vertices;
}

// Distance from p to the nearest of points.
double nearest(const std::vector<Vec3>& points, const Vec3& p) {
  double best = INFINITY;
  for (const Vec3& q : points) best = std::min(best, (q - p).norm());
  return best;
}

constexpr double kFloat = 1e-6;  // mesh files hold single precision; coordinates are ~1 m

}  // namespace

// ---------------------------------------------------------------------------
// VTU

TEST(FeaExportVtu, OurHexahedronOrderIsVtks) {
  // VTK_HEXAHEDRON's parametric corners (vtkHexahedron::GetParametricCoords):
  // the base counter-clockwise about +z, then the corners above it.
  const int vtk[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                         {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int a = 0; a < 8; ++a) {
    for (int d = 0; d < 3; ++d) EXPECT_EQ(kHexCorners[a][d], 2 * vtk[a][d] - 1) << a << " " << d;
  }
}

TEST(FeaExportVtu, GridFieldsRoundTripAtFullPrecision) {
  const HandMade made;
  const FeaMesh& mesh = made.mesh;
  TempDir dir;
  export_fea_vtu(made.structure, mesh, made.result, *made.structure.interfaces(), dir.file("r.vtu"),
                 {VtuFormat::Ascii});
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"r.vtu"});
  const std::string text = read_file(dir.file("r.vtu"));

  EXPECT_TRUE(contains(text,
                       "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" "
                       "byte_order=\"LittleEndian\">"));
  // The mesh's nodes and elements, then the ground slab's 8 corners and its cell.
  const int nodes = 2 * 27, elements = 2 * 8, points = nodes + 8, cells = elements + 1;
  ASSERT_EQ(static_cast<int>(mesh.nodes().size()), nodes);
  EXPECT_EQ(attribute(text, "NumberOfPoints"), points);
  EXPECT_EQ(attribute(text, "NumberOfCells"), cells);

  // Points and connectivity are the mesh's; every cell is a VTK hexahedron
  // (type 12) of positive volume in VTK's corner order.
  const std::vector<double> xyz = array_values(section(text, "Points"), "");
  ASSERT_EQ(xyz.size(), 3u * points);
  for (int n = 0; n < nodes; ++n) EXPECT_EQ(tuple3(xyz, n), mesh.nodes()[n]) << n;
  const std::string cell_section = section(text, "Cells");
  const std::vector<double> connectivity = array_values(cell_section, "connectivity");
  ASSERT_EQ(connectivity.size(), 8u * cells);
  EXPECT_FALSE(contains(cell_section, "faces"));  // no polyhedron
  const std::vector<double> offsets = array_values(cell_section, "offsets");
  const std::vector<double> types = array_values(cell_section, "types");
  ASSERT_EQ(offsets.size(), static_cast<size_t>(cells));
  ASSERT_EQ(types.size(), static_cast<size_t>(cells));
  for (int e = 0; e < cells; ++e) {
    EXPECT_EQ(types[e], 12);
    EXPECT_EQ(offsets[e], 8 * (e + 1));
    std::array<Vec3, 8> corner;
    for (int a = 0; a < 8; ++a) {
      if (e < elements) EXPECT_EQ(connectivity[8 * e + a], mesh.elements()[e][a]);
      else EXPECT_EQ(connectivity[8 * e + a], nodes + a);
      corner[a] = tuple3(xyz, static_cast<int>(connectivity[8 * e + a]));
    }
    EXPECT_GT((corner[1] - corner[0]).cross(corner[3] - corner[0]).dot(corner[4] - corner[0]), 0)
        << e;
  }

  // Displacements read back bit for bit.
  const std::string point_data = section(text, "PointData");
  const std::vector<double> displacement = array_values(point_data, "displacement");
  ASSERT_EQ(displacement.size(), 3u * points);
  for (int n = 0; n < nodes; ++n)
    EXPECT_EQ(tuple3(displacement, n), made.result.displacements[n]) << n;
  // The ground slab's corners, in the support cell, do not move.
  std::vector<Vec3> slab_corners;
  for (int n = nodes; n < points; ++n) {
    EXPECT_EQ(tuple3(displacement, n), Vec3::Zero()) << n;
    slab_corners.push_back(tuple3(xyz, n));
  }
  for (const Vec3& v : made.structure.block(0).vertices()) EXPECT_EQ(nearest(slab_corners, v), 0) << v.transpose();
  EXPECT_TRUE(contains(array_tag(point_data, "displacement"), "NumberOfComponents=\"3\""));

  // Contact forces act on the node's own block: + force_on_b on block b, - on block a.
  const std::vector<double> force = array_values(point_data, "contact_force");
  const std::vector<double> normal = array_values(point_data, "contact_normal_force");
  const std::vector<double> released = array_values(point_data, "released");
  ASSERT_EQ(force.size(), 3u * points);
  ASSERT_EQ(normal.size(), static_cast<size_t>(points));
  ASSERT_EQ(released.size(), static_cast<size_t>(points));
  EXPECT_EQ(tuple3(force, made.compressed), Vec3(0, 0, 100));  // cube is b of ground-cube
  EXPECT_EQ(tuple3(force, made.tensile), Vec3(1, 0, -5));      // cap is b of cube-cap
  EXPECT_EQ(tuple3(force, made.cube_top), Vec3(0, -2, -30));   // cube is a of cube-cap
  EXPECT_EQ(tuple3(force, made.released), Vec3::Zero());
  EXPECT_EQ(normal[made.compressed], 100);
  EXPECT_EQ(normal[made.tensile], -5);
  EXPECT_EQ(normal[made.cube_top], 30);
  double released_total = 0, normal_total = 0;
  for (int n = 0; n < points; ++n) {
    released_total += released[n];
    normal_total += normal[n];
  }
  EXPECT_EQ(released[made.released], 1);
  EXPECT_EQ(released_total, 1);
  EXPECT_EQ(normal_total, 125);
  EXPECT_TRUE(contains(array_tag(point_data, "released"), "type=\"Int32\""));

  // Blocks are 1-based, per node and per cell.
  const std::vector<double> node_block = array_values(point_data, "block");
  for (int n = 0; n < points; ++n) EXPECT_EQ(node_block[n], n < nodes ? mesh.node_block(n) + 1 : 1);
  const std::string cell_data = section(text, "CellData");
  const std::vector<double> cell_block = array_values(cell_data, "block");
  const std::vector<double> support = array_values(cell_data, "support");
  ASSERT_EQ(cell_block.size(), static_cast<size_t>(cells));
  ASSERT_EQ(support.size(), static_cast<size_t>(cells));
  for (int e = 0; e < cells; ++e) {
    EXPECT_EQ(cell_block[e], e < elements ? mesh.element_block(e) + 1 : 1);
    EXPECT_EQ(support[e], e < elements ? 0 : 1);
  }

  // Stress in VTK's tensor order xx yy zz xy yz xz, named; von Mises with it.
  const std::vector<double> stress = array_values(cell_data, "stress");
  const std::vector<double> mises = array_values(cell_data, "von_mises");
  ASSERT_EQ(stress.size(), 6u * cells);
  ASSERT_EQ(mises.size(), static_cast<size_t>(cells));
  const std::string stress_tag = array_tag(cell_data, "stress");
  EXPECT_TRUE(contains(stress_tag, "NumberOfComponents=\"6\"")) << stress_tag;
  EXPECT_TRUE(contains(stress_tag, "ComponentName3=\"XY\"")) << stress_tag;
  EXPECT_TRUE(contains(stress_tag, "ComponentName5=\"XZ\"")) << stress_tag;
  for (int e = 0; e < elements; ++e) {
    const Stress& s = made.result.stresses[e];
    const std::array<double, 6> vtk_order = {s(0), s(1), s(2), s(5), s(3), s(4)};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(stress[6 * e + k], vtk_order[k]) << e << " " << k;
    EXPECT_EQ(mises[e], von_mises(s));
  }
  for (int k = 0; k < 6; ++k) EXPECT_EQ(stress[6 * elements + k], 0);  // the rigid support
  EXPECT_EQ(mises[elements], 0);
}

// Element e has stress (1 + e / 3) S, so a node's mean is (1 + m / 3) S
// with m the mean index of the elements that have it as a corner: of a
// refine-2 block, a corner node is in 1 element, a face centre in 4 and the
// centre in all 8.
TEST(FeaExportVtu, NodalStressesAreTheMeansOfTheElementsAroundEachNode) {
  const HandMade made;
  const FeaMesh& mesh = made.mesh;
  TempDir dir;
  export_fea_vtu(made.structure, mesh, made.result, *made.structure.interfaces(), dir.file("r.vtu"),
                 {VtuFormat::Ascii});
  const std::string point_data = section(read_file(dir.file("r.vtu")), "PointData");
  EXPECT_TRUE(contains(point_data, "Tensors=\"nodal_stress\""));
  const std::vector<double> nodal = array_values(point_data, "nodal_stress");
  const std::vector<double> mises = array_values(point_data, "nodal_von_mises");
  ASSERT_EQ(nodal.size(), 6u * (mesh.nodes().size() + 8));
  ASSERT_EQ(mises.size(), mesh.nodes().size() + 8);
  Stress base;
  base << 1.1e5, -2.2e5, 3.3e5, 4.4e4, -5.5e4, 6.6e4;
  auto expect_mean = [&](int node, int around) {
    double index_sum = 0;
    int count = 0;
    for (size_t e = 0; e < mesh.elements().size(); ++e) {
      const auto& corners = mesh.elements()[e];
      if (std::find(corners.begin(), corners.end(), node) == corners.end()) continue;
      index_sum += static_cast<double>(e);
      ++count;
    }
    EXPECT_EQ(count, around) << node;
    const Stress s = base * (1.0 + index_sum / count / 3.0);
    const std::array<double, 6> vtk_order = {s(0), s(1), s(2), s(5), s(3), s(4)};
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(nodal[6 * node + k], vtk_order[k], 1e-12 * std::abs(vtk_order[k])) << node << " " << k;
    EXPECT_NEAR(mises[node], von_mises(s), 1e-12 * von_mises(s)) << node;
  };
  expect_mean(node_at(mesh, 1, {-0.5, -0.5, 0}), 1);  // the cube's corner
  expect_mean(node_at(mesh, 1, {0, 0, 0.5}), 8);      // its centre
  expect_mean(node_at(mesh, 2, {0.5, 0.5, 1.5}), 1);  // the cap's corner
  // The cube's top-face centre and the cap's bottom-face centre share a
  // position but not their nodes: each mean stays within its block.
  const int cube_top = node_at(mesh, 1, {0, 0, 1}), cap_bottom = node_at(mesh, 2, {0, 0, 1});
  expect_mean(cube_top, 4);
  expect_mean(cap_bottom, 4);
  EXPECT_GT(nodal[6 * cap_bottom], nodal[6 * cube_top] + 1e5);  // the cap's elements come later: larger stresses
  for (size_t n = mesh.nodes().size(); n < mesh.nodes().size() + 8; ++n) {
    for (int k = 0; k < 6; ++k) EXPECT_EQ(nodal[6 * n + k], 0) << n;  // the support's corners
  }
}

// A support that is not a hexahedron (a pentagonal slab) is one
// VTK_POLYHEDRON: its 10 vertices, its 7 faces outward in `faces`, the end
// of its face stream in `faceoffsets`, -1 for the elements.
TEST(FeaExportVtu, SupportsThatAreNoHexahedraArePolyhedra) {
  Structure s;
  std::vector<Vec3> pentagon;
  for (int k = 0; k < 5; ++k) pentagon.emplace_back(std::cos(0.4 * M_PI * k), std::sin(0.4 * M_PI * k), 0);
  s.add(std::make_shared<const Block>(make_prism(pentagon, {0, 0, -0.2})), true, "ground");
  s.add(box({0.5, 0.5, 0.5}, {0, 0, 0.25}), false, "cube");
  const FeaMesh mesh(s, 1);
  FeaResult result;
  result.displacements.assign(mesh.nodes().size(), Vec3(0, 0, -1e-6));
  TempDir dir;
  export_fea_vtu(s, mesh, result, *s.interfaces(), dir.file("r.vtu"), {VtuFormat::Ascii});
  const std::string cell_section = section(read_file(dir.file("r.vtu")), "Cells");
  EXPECT_EQ(array_values(cell_section, "types"), (std::vector<double>{12, 42}));
  EXPECT_EQ(array_values(cell_section, "offsets"), (std::vector<double>{8, 18}));
  std::vector<double> connectivity = array_values(cell_section, "connectivity");
  EXPECT_EQ(std::vector<double>(connectivity.begin() + 8, connectivity.end()),
            (std::vector<double>{8, 9, 10, 11, 12, 13, 14, 15, 16, 17}));
  const std::vector<double> faces = array_values(cell_section, "faces");
  // 7 faces: two pentagons and five quadrilaterals, each with its size.
  ASSERT_EQ(faces.size(), 1u + 2 * 6 + 5 * 5);
  EXPECT_EQ(faces[0], 7);
  EXPECT_EQ(array_values(cell_section, "faceoffsets"), (std::vector<double>{-1, 38}));
  const Block& ground = s.block(0);
  size_t at = 1;
  for (const FaceLoop& face : ground.faces()) {
    EXPECT_EQ(faces[at], static_cast<double>(face.size()));
    for (size_t k = 0; k < face.size(); ++k) EXPECT_EQ(faces[at + 1 + k], 8 + face[k]);
    at += 1 + face.size();
  }
}

// Binary is the default: VTK's compressed appended layout, and far smaller.
TEST(FeaExportVtu, BinaryIsTheDefault) {
  const HandMade made;
  TempDir dir;
  const auto& interfaces = *made.structure.interfaces();
  export_fea_vtu(made.structure, made.mesh, made.result, interfaces, dir.file("b.vtu"));
  export_fea_vtu(made.structure, made.mesh, made.result, interfaces, dir.file("a.vtu"), {VtuFormat::Ascii});
  const std::string binary = read_file(dir.file("b.vtu")), ascii = read_file(dir.file("a.vtu"));
  EXPECT_TRUE(contains(binary, "header_type=\"UInt64\" compressor=\"vtkZLibDataCompressor\""));
  EXPECT_TRUE(contains(binary, "<AppendedData encoding=\"raw\">"));
  EXPECT_FALSE(contains(binary, "format=\"ascii\""));
  EXPECT_FALSE(contains(ascii, "AppendedData"));
  EXPECT_LT(binary.size(), ascii.size() / 2);
  EXPECT_EQ(kVtuFormatNames.parse("ascii"), VtuFormat::Ascii);
  EXPECT_EQ(kVtuFormatNames.parse("binary"), VtuFormat::Binary);
}

TEST(FeaExportVtu, StressesOnlyWhenComputed) {
  HandMade made;
  made.result.stresses.clear();
  TempDir dir;
  export_fea_vtu(made.structure, made.mesh, made.result, *made.structure.interfaces(),
                 dir.file("r.vtu"), {VtuFormat::Ascii});
  const std::string text = read_file(dir.file("r.vtu"));
  EXPECT_FALSE(contains(text, "Name=\"stress\""));
  EXPECT_FALSE(contains(text, "Name=\"nodal_stress\""));
  EXPECT_FALSE(contains(text, "Name=\"nodal_von_mises\""));
  EXPECT_FALSE(contains(text, "Name=\"von_mises\""));
  EXPECT_TRUE(contains(section(text, "CellData"), "Name=\"block\""));
}

TEST(FeaExportVtu, ResultsOfAnotherMeshOrBadPathsAreRefused) {
  const HandMade made;
  TempDir dir;
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = made.structure.interfaces();
  const std::vector<Interface>& interfaces = *interfaces_list;
  auto vtu = [&](const FeaResult& result, const std::vector<Interface>& with,
                 const std::string& name) {
    return error_of(
        [&] { export_fea_vtu(made.structure, made.mesh, result, with, dir.file(name)); });
  };
  EXPECT_TRUE(contains(vtu(made.result, interfaces, "r.vtk"), ".vtu"));

  FeaResult fewer = made.result;
  fewer.displacements.pop_back();
  EXPECT_TRUE(contains(vtu(fewer, interfaces, "r.vtu"), "53 displacements but the mesh 54 nodes"));

  FeaResult bad_stresses = made.result;
  bad_stresses.stresses.pop_back();
  EXPECT_TRUE(contains(vtu(bad_stresses, interfaces, "r.vtu"), "15 stresses"));

  FeaResult not_finite = made.result;
  not_finite.displacements[3].y() = std::nan("");
  EXPECT_TRUE(contains(vtu(not_finite, interfaces, "r.vtu"), "node 4 is not finite"));

  FeaResult bad_node = made.result;
  bad_node.contacts[1].node = 54;
  EXPECT_TRUE(contains(vtu(bad_node, interfaces, "r.vtu"), "contact 2 is at node 55"));

  // Interfaces found with other options than the analysis's.
  EXPECT_TRUE(
      contains(vtu(made.result, {interfaces[0]}, "r.vtu"), "contact 2 is on interface 2 of 1"));
  EXPECT_TRUE(contains(vtu(made.result, {interfaces[1], interfaces[0]}, "r.vtu"),
                       "block 3, which interface 2 does not join"));

  // A mesh of another structure.
  Structure other;
  other.add(box({1, 1, 1}, {0, 0, 0.5}), false, "cube");
  const FeaMesh other_mesh(other, 2);
  EXPECT_TRUE(contains(error_of([&] {
                         export_fea_vtu(made.structure, other_mesh, made.result, interfaces,
                                        dir.file("r.vtu"));
                       }),
                       "displacements but the mesh 27 nodes"));
  EXPECT_TRUE(dir.entries().empty());

  EXPECT_THROW(
      export_fea_vtu(made.structure, made.mesh, made.result, interfaces, dir.file("missing/r.vtu")),
      IoError);
}

// ---------------------------------------------------------------------------
// Deformed meshes

TEST(FeaExportMesh, ObjVerticesSitAtNodePlusScaledDisplacement) {
  const HandMade made;
  TempDir dir;
  FeaMeshExportOptions options;
  options.scale = 250;
  options.contacts = false;
  export_fea_mesh(made.structure, made.mesh, made.result, dir.file("d.obj"), options);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"d.mtl", "d.obj"}));
  const std::vector<Vec3> vertices = obj_vertices(dir.file("d.obj"));

  // Every surface node (26 of the 27 per block) is drawn, the inner one not.
  int drawn = 0;
  for (size_t n = 0; n < made.mesh.nodes().size(); ++n) {
    const Vec3& x = made.mesh.nodes()[n];
    const Vec3 expected = x + options.scale * made.result.displacements[n];
    const bool inner = std::abs(x.x()) < 1e-9 && std::abs(x.y()) < 1e-9 &&
                       (std::abs(x.z() - 0.5) < 1e-9 || std::abs(x.z() - 1.25) < 1e-9);
    if (inner) {
      EXPECT_GT(nearest(vertices, expected), 1e-3) << n;
    } else {
      EXPECT_LT(nearest(vertices, expected), kFloat) << n;
      ++drawn;
    }
  }
  EXPECT_EQ(drawn, 52);
  // The ground stays where it is.
  EXPECT_LT(nearest(vertices, {1, 1, -0.5}), kFloat);
  EXPECT_LT(nearest(vertices, {-1, 1, 0}), kFloat);
}

TEST(FeaExportMesh, AutomaticScaleDrawsTheLargestDisplacementAtFivePercent) {
  const HandMade made;
  TempDir dir;
  FeaMeshExportOptions options;
  options.contacts = false;
  export_fea_mesh(made.structure, made.mesh, made.result, dir.file("d.obj"), options);
  const std::vector<Vec3> vertices = obj_vertices(dir.file("d.obj"));
  size_t largest = 0;
  for (size_t n = 0; n < made.result.displacements.size(); ++n) {
    if (made.result.displacements[n].norm() > made.result.displacements[largest].norm())
      largest = n;
  }
  const Vec3& u = made.result.displacements[largest];
  const double shown = 0.05 * made.structure.bounds().diagonal();
  EXPECT_LT(nearest(vertices, made.mesh.nodes()[largest] + shown * u.normalized()), kFloat);
}

TEST(FeaExportMesh, GltfHasBlockSurfacesSupportsAndContactNodes) {
  const HandMade made;
  TempDir dir;
  FeaMeshExportOptions options;
  options.scale = 400;
  options.undeformed = true;
  export_fea_mesh(made.structure, made.mesh, made.result, dir.file("d.gltf"), options);
  const GltfFile gltf(dir, "d.gltf");

  // Per block: 6 faces of 2 x 2 quads, 2 triangles each. The glTF writer
  // joins identical vertices; a linear field keeps each block face planar,
  // so the quads of a face share normals and each face keeps its 3 x 3 grid.
  for (const char* block : {"cube", "cap"}) {
    SCOPED_TRACE(block);
    EXPECT_EQ(gltf.triangles(block), 6 * 4 * 2);
    EXPECT_EQ(gltf.count(block, "POSITION"), 6 * 3 * 3);
    EXPECT_EQ(gltf.count(block, "COLOR_0"), 6 * 3 * 3);  // coloured by displacement
  }
  // Rotated to glTF's +Y up and back: the cap's top corner where it belongs.
  const int corner = node_at(made.mesh, 2, {0.5, 0.5, 1.5});
  const Vec3 expected =
      made.mesh.nodes()[corner] + options.scale * made.result.displacements[corner];
  EXPECT_LT(nearest(gltf.positions("cap"), expected), kFloat);

  // Supports undeformed and plain: 6 faces of 4 vertices.
  EXPECT_EQ(gltf.count("ground", "POSITION"), 24);
  EXPECT_FALSE(gltf.primitive("ground")["attributes"].contains("COLOR_0"));
  EXPECT_TRUE(gltf.has_node("cube (undeformed)"));
  EXPECT_TRUE(gltf.has_node("cap (undeformed)"));
  EXPECT_LT(nearest(gltf.positions("cube (undeformed)"), {0.5, 0.5, 1}), kFloat);

  // One octahedron each (8 triangles, 24 vertices), centred on the drawn node.
  for (const auto& [name, node] : {std::pair<std::string, int>{"tension nodes", made.tensile},
                                   {"released nodes", made.released}}) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(gltf.has_node(name));
    EXPECT_EQ(gltf.triangles(name), 8);
    Vec3 center = Vec3::Zero();
    for (const Vec3& p : gltf.positions(name)) center += p / 24.0;
    const Vec3 drawn = made.mesh.nodes()[node] + options.scale * made.result.displacements[node];
    EXPECT_LT((center - drawn).norm(), kFloat);
  }
}

TEST(FeaExportMesh, GlbReimportsAsTheAffineImageOfEachBlock) {
  const HandMade made;
  TempDir dir;
  FeaMeshExportOptions options;
  options.scale = 300;
  options.color = "block";
  options.contacts = false;
  export_fea_mesh(made.structure, made.mesh, made.result, dir.file("d.glb"), options);
  std::map<std::string, double> volumes;
  for (const ImportedBlock& b : import_blocks(dir.file("d.glb"), {}))
    volumes[b.name] = b.block.volume();
  ASSERT_EQ(volumes.size(), 3u);
  // A linear field maps each block affinely: its volume scales by det(I + s A).
  const double factor = (Mat3::Identity() + options.scale * kGradient).determinant();
  EXPECT_NEAR(volumes.at("cube"), 1.0 * factor, 1e-5);
  EXPECT_NEAR(volumes.at("cap"), 0.5 * factor, 1e-5);
  EXPECT_NEAR(volumes.at("ground"), 2.0, 1e-5);
}

TEST(FeaExportMesh, TensionIsTheAnalysisJudgement) {
  HandMade made;
  // A small negative normal force within the analysis's tolerance: round-off.
  made.result.contacts[1].tensile = false;
  TempDir dir;
  export_fea_mesh(made.structure, made.mesh, made.result, dir.file("d.gltf"), {});
  const GltfFile gltf(dir, "d.gltf");
  EXPECT_FALSE(gltf.has_node("tension nodes"));
  EXPECT_TRUE(gltf.has_node("released nodes"));
}

TEST(FeaExportMesh, EveryExtensionWrites) {
  const HandMade made;
  for (const std::string& extension : export_extensions()) {
    SCOPED_TRACE(extension);
    TempDir dir;
    export_fea_mesh(made.structure, made.mesh, made.result, dir.file("d" + extension), {});
    EXPECT_EQ(dir.entries().size(), extension == ".gltf" || extension == ".obj" ? 2u : 1u);
  }
}

TEST(FeaExportMesh, BadOptionsAreRefused) {
  const HandMade made;
  TempDir dir;
  auto export_with = [&](const FeaMeshExportOptions& options, const std::string& name = "d.glb") {
    return error_of(
        [&] { export_fea_mesh(made.structure, made.mesh, made.result, dir.file(name), options); });
  };
  for (const double scale : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    FeaMeshExportOptions options;
    options.scale = scale;
    EXPECT_TRUE(contains(export_with(options), "scale must be a finite number >= 0")) << scale;
  }
  FeaMeshExportOptions colour;
  colour.color = "stress";
  const std::string message = export_with(colour);
  EXPECT_TRUE(contains(message, "unknown color 'stress'")) << message;
  EXPECT_TRUE(contains(message, "'displacement', 'block'")) << message;

  FeaMeshExportOptions map;
  map.map = "jet";
  EXPECT_TRUE(contains(export_with(map), "'viridis'"));

  const std::string extension = export_with({}, "d.dae");
  EXPECT_TRUE(contains(extension, ".glb, .gltf, .obj, .ply, .stl")) << extension;

  FeaResult fewer = made.result;
  fewer.displacements.pop_back();
  EXPECT_THROW(export_fea_mesh(made.structure, made.mesh, fewer, dir.file("d.glb"), {}),
               InvalidArgument);
  EXPECT_TRUE(dir.entries().empty());

  EXPECT_THROW(export_fea_mesh(made.structure, made.mesh, made.result, dir.file("no/d.glb"), {}),
               IoError);
}
