// Mesh files through assimp (import of OBJ, STL, PLY, glTF; export to every
// supported extension, atomically) and the colour maps used for export.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "geometry/block_builders.hpp"
#include "core/atomic_file.hpp"
#include "io/color_map.hpp"
#include "io/force_glyphs.hpp"
#include "io/mesh_io.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

const std::string kMeshData = std::string(ASHLAR_TEST_DATA) + "/mesh/";

std::map<std::string, const Block*> by_name(const std::vector<ImportedBlock>& blocks) {
  std::map<std::string, const Block*> result;
  for (const ImportedBlock& b : blocks) result[b.name] = &b.block;
  return result;
}

// Blocks with coordinates that single-precision mesh files hold exactly,
// including a non-convex L-shaped prism whose top and bottom faces need
// real ear clipping, and contacts between them for interface export.
Structure float_exact_structure() {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({4, 2, 0.5}, {0, 0, -0.25})), true, "ground");
  const std::vector<Vec3> l_shape = {{-1, -0.5, 0}, {1, -0.5, 0}, {1, 0, 0},
                                     {0, 0, 0},     {0, 0.5, 0},  {-1, 0.5, 0}};
  s.add(std::make_shared<const Block>(make_prism(l_shape, {0, 0, 1})), false, "L block");
  s.add(std::make_shared<const Block>(make_box({1, 0.5, 0.25}, {-0.5, 0.25, 1.125})), false,
        "cap");
  s.add(std::make_shared<const Block>(
            make_hull({{1.5, -1, 0}, {2, -1, 0}, {2, -0.5, 0}, {1.75, -0.75, 0.75}})),
        false, "wedge");
  return s;
}

void expect_same_blocks(const Structure& original, const std::vector<ImportedBlock>& imported) {
  ASSERT_EQ(imported.size(), static_cast<size_t>(original.size()));
  const auto blocks = by_name(imported);
  const double size = original.bounds().diagonal();
  for (int i = 0; i < original.size(); ++i) {
    SCOPED_TRACE(original.name(i));
    ASSERT_EQ(blocks.count(original.name(i)), 1u);
    const Block& copy = *blocks.at(original.name(i));
    const Block& block = original.block(i);
    EXPECT_NEAR(copy.volume(), block.volume(), 1e-12 * block.volume());
    EXPECT_LT((copy.centroid() - block.centroid()).norm(), 1e-12 * size);
    EXPECT_EQ(copy.faces().size(), block.faces().size());
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// Import

TEST(MeshImport, ObjWithTwoObjects) {
  ImportOptions options;
  options.density = 2000;
  const auto blocks = import_blocks(kMeshData + "two_objects.obj", options);
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].name, "wall_1");
  EXPECT_EQ(blocks[1].name, "wall_2");
  EXPECT_NEAR(blocks[0].block.volume(), 1.0, 1e-12);
  EXPECT_NEAR(blocks[1].block.volume(), 0.5, 1e-12);
  EXPECT_EQ(blocks[0].block.faces().size(), 6u);
  EXPECT_EQ(blocks[0].block.name(), "wall_1");
  EXPECT_EQ(blocks[1].block.density(), 2000);
}

TEST(MeshImport, StlTrianglesBecomeSixFacedCube) {
  for (const char* file : {"cube_ascii.stl", "cube_binary.stl"}) {
    SCOPED_TRACE(file);
    const auto blocks = import_blocks(kMeshData + file, {});
    ASSERT_EQ(blocks.size(), 1u);
    const Block& cube = blocks[0].block;
    EXPECT_EQ(cube.vertices().size(), 8u);
    EXPECT_EQ(cube.faces().size(), 6u);
    EXPECT_NEAR(cube.volume(), 8.0, 1e-12);
    EXPECT_LT((cube.centroid() - Vec3(1, 1, 1)).norm(), 1e-12);
    EXPECT_FALSE(blocks[0].name.empty());
  }
}

TEST(MeshImport, PlyPolygonsOfANonConvexPrism) {
  const auto blocks = import_blocks(kMeshData + "l_prism.ply", {});
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_NEAR(blocks[0].block.volume(), 3.0, 1e-12);
  EXPECT_EQ(blocks[0].block.faces().size(), 8u);
  EXPECT_FALSE(blocks[0].block.convex());
}

TEST(MeshImport, GltfNodeTransformsAndAxesApply) {
  // A unit tetrahedron scaled by 2 in a child of a node translated by 10
  // along glTF's x; glTF's +Y up becomes ashlar's +Z up.
  const auto blocks = import_blocks(kMeshData + "nested_transforms.gltf", {});
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].name, "scaled tetra");
  EXPECT_NEAR(blocks[0].block.volume(), 4.0 / 3.0, 1e-12);
  EXPECT_LT((blocks[0].block.centroid() - Vec3(10.5, -0.5, 0.5)).norm(), 1e-12);
}

TEST(MeshImport, RepeatedNamesAreMadeUnique) {
  // Two nodes of one name (OBJ would merge them into one object; glTF keeps
  // nodes apart).
  auto gltf = nlohmann::json::parse(read_file(kMeshData + "nested_transforms.gltf"));
  gltf["nodes"].push_back({{"name", "scaled tetra"}, {"mesh", 0}, {"translation", {0, 5, 0}}});
  gltf["nodes"][0]["children"].push_back(2);
  TempDir dir;
  write_file_atomically(dir.file("twice.gltf"), gltf.dump());
  const auto blocks = import_blocks(dir.file("twice.gltf"), {});
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].name, "scaled tetra");
  EXPECT_EQ(blocks[1].name, "scaled tetra#2");
  EXPECT_NEAR(blocks[1].block.volume(), 1.0 / 6.0, 1e-12);
}

TEST(MeshImport, OpenMeshIsAGeometryErrorNamingTheObject) {
  try {
    import_blocks(kMeshData + "open_box.obj", {});
    FAIL() << "an open box was accepted";
  } catch (const GeometryError& e) {
    EXPECT_TRUE(contains(e.what(), "object 'open_box' in '" + kMeshData + "open_box.obj'"))
        << e.what();
  }
}

TEST(MeshImport, UnreadableFilesAreIoErrorsNamingThePath) {
  const std::string missing = "/nonexistent/ashlar/model.obj";
  const std::string message = error_of([&] { import_blocks(missing, {}); });
  EXPECT_TRUE(contains(message, "'" + missing + "'")) << message;

  TempDir dir;
  write_file_atomically(dir.file("junk.glb"), "glTF but not really");
  EXPECT_THROW(import_blocks(dir.file("junk.glb"), {}), IoError);
  write_file_atomically(dir.file("empty.obj"), "# nothing here\n");
  EXPECT_THROW(import_blocks(dir.file("empty.obj"), {}), IoError);
}

// assimp's PLY reader would never return on these: the import refuses them.
TEST(MeshImport, PlyHeaderWithoutEndHeaderIsAnIoError) {
  TempDir dir;
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n";
  for (const char* name : {"open.ply", "open.obj.txt"}) {
    write_file_atomically(dir.file(name), header + "end_headerx\n0\n1\n2\n");
    const std::string message = error_of([&] { import_blocks(dir.file(name), {}); });
    EXPECT_TRUE(contains(message, "'" + dir.file(name) + "': its PLY header has no end_header line"))
        << message;
  }
  for (const std::string magic : {"PLY", "pLyYYY"}) {
    const std::string name = magic + ".ply";
    write_file_atomically(dir.file(name), magic + header.substr(3));
    const std::string message = error_of([&] { import_blocks(dir.file(name), {}); });
    EXPECT_TRUE(contains(message, "'" + dir.file(name) + "': its PLY header has no end_header line"))
        << message;
  }
  write_file_atomically(dir.file("closed.ply"), header + "  end_header\r\n0\n1\n2\n");
  const std::string message = error_of([&] { import_blocks(dir.file("closed.ply"), {}); });
  EXPECT_FALSE(contains(message, "end_header")) << message;  // assimp reads it, and finds no faces
}

TEST(MeshImport, RejectsBadOptions) {
  ImportOptions options;
  options.density = -1;
  EXPECT_THROW(import_blocks(kMeshData + "cube_ascii.stl", options), InvalidArgument);
  options = {};
  options.relative_weld_tolerance = std::nan("");
  EXPECT_THROW(import_blocks(kMeshData + "cube_ascii.stl", options), InvalidArgument);
}

// ---------------------------------------------------------------------------
// Export

TEST(MeshExport, GltfRoundTripKeepsNamesAndVolumes) {
  TempDir dir;
  const Structure s = float_exact_structure();
  for (const char* name : {"s.glb", "s.gltf", "s.obj"}) {
    SCOPED_TRACE(name);
    export_structure(s, dir.file(name), {});
    expect_same_blocks(s, import_blocks(dir.file(name), {}));
  }
}

TEST(MeshExport, NonConvexFacesWithCollinearVerticesAreTriangulated) {
  // A comb with three teeth; its bottom edge has two straight-angle
  // vertices, which a careless ear clipper turns into zero-area ears.
  const std::vector<Vec3> comb = {
      {0, 0, 0},       {0.5, 0, 0},    {1, 0, 0},        {1.75, 0, 0},     {1.75, 1, 0},
      {1.5, 1, 0},     {1.5, 0.25, 0}, {1, 0.25, 0},     {1, 1, 0},        {0.75, 1, 0},
      {0.75, 0.25, 0}, {0.25, 0.25, 0}, {0.25, 1, 0},    {0, 1, 0}};
  Structure s;
  s.add(std::make_shared<const Block>(make_prism(comb, {0, 0, 0.5})), false, "comb");
  TempDir dir;
  export_structure(s, dir.file("comb.glb"), {});
  const auto blocks = import_blocks(dir.file("comb.glb"), {});
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_NEAR(blocks[0].block.volume(), s.block(0).volume(), 1e-12 * s.block(0).volume());
  EXPECT_LT((blocks[0].block.centroid() - s.block(0).centroid()).norm(), 1e-12);
}

TEST(MeshExport, EveryExtensionWritesWholeFilesOnly) {
  const Structure s = float_exact_structure();
  const std::map<std::string, std::vector<std::string>> expected_files = {
      {".glb", {"s.glb"}},
      {".gltf", {"s.bin", "s.gltf"}},
      {".obj", {"s.mtl", "s.obj"}},
      {".ply", {"s.ply"}},
      {".stl", {"s.stl"}},
  };
  ASSERT_EQ(export_extensions().size(), expected_files.size());
  for (const std::string& extension : export_extensions()) {
    SCOPED_TRACE(extension);
    TempDir dir;
    ExportOptions options;
    options.interfaces = true;
    export_structure(s, dir.file("s" + extension), options);
    EXPECT_EQ(dir.entries(), expected_files.at(extension));
    for (const auto& name : dir.entries()) {
      struct stat info {};
      ASSERT_EQ(::stat(dir.file(name).c_str(), &info), 0);
      EXPECT_GT(info.st_size, 0) << name;
    }
  }
}

TEST(MeshExport, GltfHasNodesMaterialsAndFlatShading) {
  TempDir dir;
  const Structure s = float_exact_structure();
  ExportOptions options;
  options.interfaces = true;
  options.block_colors = map_colors({0, 1, 2, 3}, 0, 3, "viridis");
  export_structure(s, dir.file("s.gltf"), options);
  const auto gltf = nlohmann::json::parse(read_file(dir.file("s.gltf")));

  // The buffer is referenced by its bare name, next to the .gltf.
  EXPECT_EQ(gltf["buffers"][0]["uri"], "s.bin");

  std::map<std::string, nlohmann::json> nodes;
  for (const auto& node : gltf["nodes"]) nodes[node.value("name", "")] = node;
  for (int i = 0; i < s.size(); ++i) EXPECT_EQ(nodes.count(s.name(i)), 1u) << s.name(i);
  EXPECT_EQ(nodes.count("interface 1-2"), 1u);  // ground under the L block
  EXPECT_EQ(nodes.count("interface 2-3"), 1u);  // L block under the cap

  // The ground box: 6 faces of 4 vertices each, 12 triangles.
  const auto& mesh = gltf["meshes"][nodes["ground"]["mesh"].get<int>()];
  const auto& primitive = mesh["primitives"][0];
  EXPECT_EQ(gltf["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"], 24);
  EXPECT_EQ(gltf["accessors"][primitive["indices"].get<int>()]["count"], 36);

  const auto& material = gltf["materials"][primitive["material"].get<int>()];
  const auto& base_color = material["pbrMetallicRoughness"]["baseColorFactor"];
  EXPECT_NEAR(base_color[0].get<double>(), options.block_colors[0].r, 1e-6);
  EXPECT_NEAR(base_color[1].get<double>(), options.block_colors[0].g, 1e-6);
}

TEST(MeshExport, ExtensionIsCaseInsensitive) {
  TempDir dir;
  export_structure(float_exact_structure(), dir.file("S.GLB"), {});
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"S.GLB"});
}

TEST(MeshExport, UnknownExtensionListsTheSupportedOnes) {
  TempDir dir;
  for (const char* name : {"s.dae", "no_extension", "folder.glb/s"}) {
    const std::string message =
        error_of([&] { export_structure(float_exact_structure(), dir.file(name), {}); });
    EXPECT_TRUE(contains(message, ".glb, .gltf, .obj, .ply, .stl")) << message;
  }
  EXPECT_TRUE(dir.entries().empty());
}

TEST(MeshExport, FailedExportLeavesNoFile) {
  TempDir dir;
  const Structure s = float_exact_structure();
  const std::string message =
      error_of([&] { export_structure(s, dir.file("missing/folder/s.glb"), {}); });
  EXPECT_TRUE(contains(message, dir.file("missing/folder/s.glb"))) << message;

  for (const std::string& extension : export_extensions()) {
    EXPECT_THROW(export_structure(s, dir.file("missing/s" + extension), {}), IoError);
  }
  EXPECT_TRUE(dir.entries().empty());

  // A folder has the target's name: the data is written, the rename fails.
  ASSERT_EQ(::mkdir(dir.file("taken.glb").c_str(), 0755), 0);
  EXPECT_THROW(export_structure(s, dir.file("taken.glb"), {}), IoError);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.glb"});
  ::rmdir(dir.file("taken.glb").c_str());
}

TEST(MeshExport, RejectsBadColours) {
  TempDir dir;
  const Structure s = float_exact_structure();
  ExportOptions options;
  options.block_colors = {Rgb{}};
  EXPECT_THROW(export_structure(s, dir.file("s.glb"), options), InvalidArgument);
  options.block_colors.assign(s.size(), Rgb{});
  options.block_colors[2].g = std::nan("");
  const std::string message = error_of([&] { export_structure(s, dir.file("s.glb"), options); });
  EXPECT_TRUE(contains(message, "colour 3")) << message;
  EXPECT_TRUE(dir.entries().empty());
}

// ---------------------------------------------------------------------------
// Forces and thrust lines

TEST(ColorMap, EndsMiddleAndClamping) {
  const auto colors = map_colors({-5, 0, 5, 10, 20}, 0, 10, "viridis");
  ASSERT_EQ(colors.size(), 5u);
  EXPECT_NEAR(colors[0].r, 0.267004, 1e-12);  // below the range: first colour
  EXPECT_NEAR(colors[1].b, 0.329415, 1e-12);
  EXPECT_NEAR(colors[2].g, 0.5657, 1e-3);     // viridis(0.5), greenish teal
  EXPECT_NEAR(colors[3].r, 0.993248, 1e-12);
  EXPECT_NEAR(colors[4].g, 0.906157, 1e-12);  // above the range: last colour

  const auto gray = map_colors({0.25}, 0, 1, "grayscale");
  EXPECT_DOUBLE_EQ(gray[0].r, 0.25);
  EXPECT_DOUBLE_EQ(gray[0].b, 0.25);
  // A reversed range reverses the map.
  EXPECT_DOUBLE_EQ(map_colors({0.25}, 1, 0, "grayscale")[0].g, 0.75);
}

TEST(ColorMap, EveryMapStaysInTheUnitCube) {
  EXPECT_GE(color_map_names().size(), 4u);
  std::vector<double> values;
  for (int k = 0; k <= 100; ++k) values.push_back(k / 100.0);
  for (const std::string& name : color_map_names()) {
    for (const Rgb& c : map_colors(values, 0, 1, name)) {
      for (double component : {c.r, c.g, c.b}) {
        EXPECT_GE(component, 0.0) << name;
        EXPECT_LE(component, 1.0) << name;
      }
    }
  }
  const auto diverging = map_colors({0.5}, 0, 1, "coolwarm");
  EXPECT_NEAR(diverging[0].r, diverging[0].b, 1e-6);  // neutral grey in the middle
}

TEST(ColorMap, DegenerateRangeAndBadInput) {
  const auto flat = map_colors({3, 3, 4}, 3, 3, "grayscale");
  for (const Rgb& c : flat) EXPECT_DOUBLE_EQ(c.r, 0.5);

  const std::string nan_message = error_of([] { map_colors({1, std::nan(""), 2}, 0, 1, "magma"); });
  EXPECT_TRUE(contains(nan_message, "value 2 of 3")) << nan_message;
  EXPECT_TRUE(contains(nan_message, "NaN")) << nan_message;

  const std::string map_message = error_of([] { map_colors({1}, 0, 1, "jet"); });
  EXPECT_TRUE(contains(map_message, "'viridis', 'magma', 'coolwarm', 'grayscale'")) << map_message;
  EXPECT_THROW(map_colors({1}, 0, INFINITY, "viridis"), InvalidArgument);
}
