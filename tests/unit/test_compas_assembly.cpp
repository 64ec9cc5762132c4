// COMPAS Assembly files: the forces ashlar writes balance every block by
// the conventions compas_rbe's equilibrium matrix states, and hand-made
// files of the three layouts read as the same assembly.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/atomic_file.hpp"
#include "io/compas_assembly.hpp"
#include "structure/structure_transform.hpp"
#include "test_support.hpp"

namespace {

using ashlar::Vec3;
using Json = nlohmann::json;

Vec3 vec3(const Json& v) { return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()}; }

std::string data_file(const std::string& name) { return std::string(ASHLAR_TEST_DATA) + "/compas/" + name; }

TEST(CompasAssembly, ExportedForcesBalanceEveryBlock) {
  // A semicircular arch turned about a skew axis, so that forces and friction
  // have components along all three axes, under a sideways point load.
  ashlar::Structure s = ashlar::rotated(semicircular_arch(16, 0.8), Vec3(0.3, 1.0, 0.2), 0.15, Vec3::Zero());
  s.add_load({5, Vec3(2000.0, 500.0, 0.0), s.block(5).centroid() + Vec3(0, 0, 0.3)});
  const ashlar::EquilibriumResult result = ashlar::analyze_equilibrium(s, with_friction(0.7));
  ASSERT_EQ(result.status, ashlar::SolverStatus::converged);
  ashlar::CompasExportOptions options;
  options.result = &result;
  const Json document = Json::parse(ashlar::compas_assembly_json(s, options));
  EXPECT_EQ(document["dtype"], "compas_assembly.datastructures/Assembly");
  const Json& graph = document["data"]["graph"]["data"];

  // Force and moment (about each block's centroid) of every contact force,
  // read with compas_rbe's conventions: on v, (c_np - c_nn) z + c_u x + c_v y
  // with z = xaxis x yaxis; on u, its opposite.
  const int n = s.size();
  std::vector<Vec3> force(n, Vec3::Zero()), moment(n, Vec3::Zero());
  int interfaces = 0;
  for (const auto& [u, neighbours] : graph["edge"].items()) {
    for (const auto& [v, attributes] : neighbours.items()) {
      const int a = std::stoi(u), b = std::stoi(v);
      for (const Json& entry : attributes["interfaces"]) {
        ++interfaces;
        EXPECT_EQ(entry["dtype"], "compas_assembly.datastructures/Interface");
        const Json& data = entry["data"];
        const Json& frame = data["frame"]["data"];
        const Vec3 x = vec3(frame["xaxis"]), y = vec3(frame["yaxis"]), z = x.cross(y);
        ASSERT_EQ(data["points"].size(), data["forces"].size());
        for (size_t k = 0; k < data["points"].size(); ++k) {
          const Vec3 p = vec3(data["points"][k]);
          const Json& f = data["forces"][k];
          const Vec3 on_b = (f["c_np"].get<double>() - f["c_nn"].get<double>()) * z + f["c_u"].get<double>() * x +
                            f["c_v"].get<double>() * y;
          force[b] += on_b;
          moment[b] += (p - s.block(b).centroid()).cross(on_b);
          force[a] -= on_b;
          moment[a] -= (p - s.block(a).centroid()).cross(on_b);
        }
      }
    }
  }
  EXPECT_EQ(interfaces, static_cast<int>(s.interfaces()->size()));
  double total_weight = 0.0;
  for (int i = 0; i < n; ++i) total_weight += ashlar::kGravity * s.block(i).mass();
  for (const ashlar::PointLoad& load : s.loads()) {
    force[load.block] += load.force;
    moment[load.block] += (load.at - s.block(load.block).centroid()).cross(load.force);
  }
  for (int i = 0; i < n; ++i) {
    if (s.is_support(i)) continue;
    const Vec3 weight(0.0, 0.0, -ashlar::kGravity * s.block(i).mass());
    EXPECT_LT((force[i] + weight).norm(), 1e-7 * total_weight) << "block " << i + 1;
    EXPECT_LT(moment[i].norm(), 1e-7 * total_weight * 5.0) << "block " << i + 1;  // arms up to 5 m
  }
}

TEST(CompasAssembly, ReadsTheThreeLayoutsAsOneAssembly) {
  const std::pair<const char*, const char*> files[] = {{"stack_compas2.json", "compas 2"},
                                                       {"stack_compas1.json", "compas 1"},
                                                       {"stack_assembly0.json", "compas_assembly 0.x"}};
  for (const auto& [file, layout] : files) {
    SCOPED_TRACE(file);
    const ashlar::CompasAssembly assembly = ashlar::read_compas_assembly(data_file(file), {});
    EXPECT_EQ(assembly.layout, layout);
    ASSERT_EQ(assembly.blocks.size(), 3u);
    EXPECT_EQ(assembly.supports, (std::vector<bool>{true, false, false}));
    EXPECT_NEAR(assembly.blocks[0].block.volume(), 2.0, 1e-12);
    EXPECT_NEAR(assembly.blocks[1].block.volume(), 1.0, 1e-12);
    EXPECT_NEAR(assembly.blocks[2].block.volume(), 0.25, 1e-12);
    EXPECT_LT((assembly.blocks[1].block.centroid() - Vec3(0.2, 0.0, 0.5)).norm(), 1e-12);
    // The mesh's own name, unless it is only the class default.
    EXPECT_EQ(assembly.blocks[1].name, "node 1");
    ASSERT_EQ(assembly.interfaces.size(), 2u);
    EXPECT_EQ(assembly.interfaces[1].a, 1);
    EXPECT_EQ(assembly.interfaces[1].b, 2);
    ASSERT_TRUE(assembly.interfaces[1].normal.has_value());
    EXPECT_LT((*assembly.interfaces[1].normal - Vec3(0, 0, 1)).norm(), 1e-15);
    EXPECT_EQ(assembly.interfaces[1].points.size(), 4u);

    const ashlar::Structure s = ashlar::compas_structure(assembly, true, {});
    ASSERT_EQ(s.interfaces()->size(), 2u);
    EXPECT_NEAR((*s.interfaces())[0].area, 1.0, 1e-12);
    EXPECT_NEAR((*s.interfaces())[1].area, 0.45, 1e-12);
    EXPECT_TRUE((*s.interfaces())[1].is_explicit);
    // Each joint carries the weight above it: W1 + W2, then W2.
    const ashlar::EquilibriumResult r = ashlar::analyze_equilibrium(s, with_friction(0.5));
    EXPECT_TRUE(r.stable);
    const double w1 = ashlar::kGravity * s.block(1).mass(), w2 = ashlar::kGravity * s.block(2).mass();
    EXPECT_NEAR(r.interfaces[0].normal_force, w1 + w2, 1e-6 * (w1 + w2));
    EXPECT_NEAR(r.interfaces[1].normal_force, w2, 1e-6 * w2);
  }
}

TEST(CompasAssembly, NamesTheEntryAtFault) {
  TempDir folder;
  const std::string path = folder.file("bad.json");
  auto message = [&](const std::string& text) {
    ashlar::write_file_atomically(path, text);
    return error_of([&] { ashlar::read_compas_assembly(path, {}); });
  };
  EXPECT_TRUE(contains(message(R"({"blocks": []})"),
                       "top level: not a COMPAS Assembly: expected a \"graph\" (compas 1 and 2) or \"assembly\" "
                       "and \"blocks\" (compas_assembly 0.x), got the fields blocks"))
      << message(R"({"blocks": []})");
  const std::string no_block = R"({"graph": {"node": {"0": {"is_support": true}}}})";
  EXPECT_TRUE(contains(message(no_block), "graph.node.0: the node has no block")) << message(no_block);
  const std::string bad_flag =
      R"({"graph": {"node": {"0": {"block": {"vertex": {}, "face": {}}, "is_support": "yes"}}}})";
  EXPECT_TRUE(contains(message(bad_flag), "graph.node.0.is_support: expected true or false, got \"yes\""))
      << message(bad_flag);
  const std::string missing_vertex =
      R"({"graph": {"node": {"0": {"block": {"vertex": {"0": {"x": 0}}, "face": {"0": [0, 7, 0]}}}}}})";
  EXPECT_TRUE(contains(message(missing_vertex), "graph.node.0.block.face.0[1]: vertex 7 does not exist"))
      << message(missing_vertex);
  // Python's json module writes NaN bare; the reader names where.
  const std::string nan = R"({"graph": {"node": {"0": {"block": {"vertex": {"0": {"x": NaN}}, "face": {}}}}}})";
  EXPECT_TRUE(contains(message(nan), "graph.node.0.block.vertex.0.x: expected a finite number")) << message(nan);
  EXPECT_TRUE(contains(message("{"), "not valid JSON")) << message("{");

  // An interface add_interface refuses is named by its place in the file.
  std::ifstream in(data_file("stack_compas2.json"));
  Json document = Json::parse(in);
  Json& points = document["data"]["graph"]["data"]["edge"]["1"]["2"]["interfaces"][0]["data"]["points"];
  points[2] = {0.7, 0.25, 1.4};
  ashlar::write_file_atomically(path, document.dump());
  const ashlar::CompasAssembly assembly = ashlar::read_compas_assembly(path, {});
  const std::string refused = error_of([&] { ashlar::compas_structure(assembly, true, {}); });
  EXPECT_TRUE(contains(refused, path + ": graph.edge.1.2.interfaces[0]: interface between block 2 ('node 1') and "
                                       "block 3 ('top'), polygon 1: not planar"))
      << refused;
}

}  // namespace
