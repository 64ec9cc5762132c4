// The structure file format: exact round trip, strict and explicit rejection
// of bad files, and the whole-or-nothing file writes underneath.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>

#include "core/error.hpp"
#include "geometry/block_builders.hpp"
#include "core/atomic_file.hpp"
#include "io/structure_json.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

void expect_bitwise_equal(const Vec3& a, const Vec3& b) {
  for (int k = 0; k < 3; ++k) EXPECT_EQ(bits(a[k]), bits(b[k])) << a[k] << " vs " << b[k];
}

// Blocks whose coordinates have no short decimal form, so that only an
// exact round trip reproduces them.
Structure awkward_structure() {
  Structure s;
  std::mt19937_64 random(20240521);
  std::uniform_real_distribution<double> jitter(-1.0, 1.0);
  const Block base = make_box({1.0 / 3.0, 0.1, M_PI / 7.0}, {0, 0, 0});
  s.add(std::make_shared<const Block>(base.translated({0.1, 0.2, 0.3})), true, "ground");
  for (int i = 0; i < 4; ++i) {
    const Vec3 offset(jitter(random) * 1e3, jitter(random) * 1e-3, 1.0 + i * M_PI / 7.0);
    const Block moved = base.rotated({jitter(random), jitter(random), 1.0}, jitter(random),
                                     Vec3::Zero())
                            .translated(offset)
                            .with_density(2000.0 + jitter(random));
    s.add(std::make_shared<const Block>(moved), false, "voussoir " + std::to_string(i + 1));
  }
  s.add(std::make_shared<const Block>(make_prism(
            {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, {0, 0, 0.7})),
        false, "L \"quoted\" / ünïcode");
  s.add_load({1, {0.1, -1.0 / 3.0, -9.81 * 2400.0}, {1.0 / 7.0, 2.0 / 3.0, 1e-300}});
  // Extremes of the double range survive too (loads take any finite value).
  s.add_load({2,
              {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(), -0.0},
              {std::numeric_limits<double>::min(), -std::numeric_limits<double>::max(), 5e-324}});
  return s;
}

void expect_same_structure(const Structure& a, const Structure& b) {
  ASSERT_EQ(a.size(), b.size());
  for (int i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("block " + std::to_string(i));
    EXPECT_EQ(a.name(i), b.name(i));
    EXPECT_EQ(a.is_support(i), b.is_support(i));
    EXPECT_EQ(bits(a.block(i).density()), bits(b.block(i).density()));
    ASSERT_EQ(a.block(i).vertices().size(), b.block(i).vertices().size());
    for (size_t v = 0; v < a.block(i).vertices().size(); ++v) {
      expect_bitwise_equal(a.block(i).vertices()[v], b.block(i).vertices()[v]);
    }
    EXPECT_EQ(a.block(i).faces(), b.block(i).faces());
    EXPECT_EQ(bits(a.block(i).volume()), bits(b.block(i).volume()));
  }
  ASSERT_EQ(a.loads().size(), b.loads().size());
  for (size_t k = 0; k < a.loads().size(); ++k) {
    EXPECT_EQ(a.loads()[k].block, b.loads()[k].block);
    expect_bitwise_equal(a.loads()[k].force, b.loads()[k].force);
    expect_bitwise_equal(a.loads()[k].at, b.loads()[k].at);
  }
}

// A valid one-block document to break in the rejection tests.
nlohmann::json minimal_document() {
  return nlohmann::json::parse(R"({
    "format": "ashlar-structure", "version": 1,
    "blocks": [{"name": "cube", "vertices": [[0,0,0],[1,0,0],[1,1,0],[0,1,0],
                                             [0,0,1],[1,0,1],[1,1,1],[0,1,1]],
                "faces": [[0,3,2,1],[4,5,6,7],[0,1,5,4],[1,2,6,5],[2,3,7,6],[3,0,4,7]]}]
  })");
}

std::string load_error(const nlohmann::json& document) {
  try {
    structure_from_json(document.dump(), "test.json");
  } catch (const IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted: " << document.dump();
  return {};
}

}  // namespace

TEST(StructureJson, RoundTripIsBitExact) {
  const Structure original = awkward_structure();
  const Structure copy = structure_from_json(structure_to_json(original), "memory");
  expect_same_structure(original, copy);
  // A second cycle writes the very same text.
  EXPECT_EQ(structure_to_json(original), structure_to_json(copy));
}

TEST(StructureJson, SaveAndLoadThroughAFile) {
  TempDir dir;
  const Structure original = awkward_structure();
  save_structure(original, dir.file("s.json"));
  expect_same_structure(original, load_structure(dir.file("s.json")));
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"s.json"});
}

TEST(StructureJson, DocumentFollowsTheSchema) {
  const auto document = nlohmann::json::parse(structure_to_json(awkward_structure()));
  EXPECT_EQ(document["format"], "ashlar-structure");
  EXPECT_EQ(document["version"], kStructureFormatVersion);
  EXPECT_EQ(document["units"], nlohmann::json({{"length", "m"}, {"mass", "kg"}, {"force", "N"}}));
  ASSERT_EQ(document["blocks"].size(), 6u);
  const auto& ground = document["blocks"][0];
  EXPECT_EQ(ground["name"], "ground");
  EXPECT_EQ(ground["support"], true);
  EXPECT_EQ(ground["vertices"].size(), 8u);
  EXPECT_EQ(ground["vertices"][0].size(), 3u);
  EXPECT_EQ(ground["faces"].size(), 6u);
  EXPECT_EQ(document["loads"][0]["block"], 1);
}

TEST(StructureJson, NamesMustBeUtf8ToBeSaved) {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({1, 1, 1}, {0, 0, 0})), false, "ok");
  s.add(std::make_shared<const Block>(make_box({1, 1, 1}, {0, 0, 1})), false, "bad \xff");
  try {
    structure_to_json(s);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("block 2 is not valid UTF-8"), std::string::npos);
  }
}

TEST(StructureJson, OptionalFieldsTakeTheirDefaults) {
  nlohmann::json document = minimal_document();
  document["blocks"][0].erase("name");
  const Structure s = structure_from_json(document.dump(), "minimal");
  ASSERT_EQ(s.size(), 1);
  EXPECT_FALSE(s.is_support(0));
  EXPECT_EQ(s.block(0).density(), kDefaultDensity);
  EXPECT_EQ(s.name(0), "block 1");
  EXPECT_DOUBLE_EQ(s.block(0).volume(), 1.0);
  EXPECT_TRUE(s.loads().empty());
}

TEST(StructureJson, RejectsOtherFormatsAndVersions) {
  nlohmann::json document = minimal_document();
  document["format"] = "something-else";
  EXPECT_NE(load_error(document).find("expected \"ashlar-structure\""), std::string::npos);

  document = minimal_document();
  document["version"] = 2;
  const std::string message = load_error(document);
  EXPECT_NE(message.find("unsupported version 2"), std::string::npos) << message;
  EXPECT_NE(message.find("reads version 1"), std::string::npos) << message;

  document = minimal_document();
  document["units"] = {{"length", "mm"}};
  EXPECT_NE(load_error(document).find("units.length: unsupported unit \"mm\""), std::string::npos);
}

TEST(StructureJson, NamesTheOffendingEntry) {
  struct Case {
    std::function<void(nlohmann::json&)> damage;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {[](auto& d) { d.erase("blocks"); }, "test.json: missing field 'blocks'"},
      {[](auto& d) { d["blocks"][0]["vertices"][2] = {1, 2}; },
       "test.json: blocks[0].vertices[2]: expected 3 finite numbers"},
      {[](auto& d) { d["blocks"][0]["vertices"][3][1] = "1"; },
       "blocks[0].vertices[3]: expected 3 finite numbers"},
      {[](auto& d) { d["blocks"][0]["faces"][1][2] = 8; },
       "blocks[0].faces[1][2]: index 8 is out of range (8 vertices, 0-based)"},
      {[](auto& d) { d["blocks"][0]["faces"][1][0] = -1; }, "blocks[0].faces[1][0]: index -1"},
      {[](auto& d) { d["blocks"][0]["faces"][0][0] = 1.5; },
       "blocks[0].faces[0][0]: expected an integer index"},
      {[](auto& d) { d["blocks"][0]["faces"] = "all"; }, "blocks[0].faces: expected an array"},
      {[](auto& d) { d["blocks"][0].erase("faces"); }, "blocks[0]: missing field 'faces'"},
      {[](auto& d) { d["blocks"][0]["support"] = "yes"; },
       "blocks[0].support: expected true or false"},
      {[](auto& d) { d["blocks"][0]["density"] = -5; }, "blocks[0].density: must be positive"},
      {[](auto& d) { d["blocks"][0]["desnity"] = 2000; },
       "blocks[0]: unknown field 'desnity' (allowed: density, faces, name, planarity, support, vertices)"},
      {[](auto& d) { d["blocks"][1] = d["blocks"][0]; },
       "blocks[1] ('cube'): structure add: the name 'cube' is already used"},
      {[](auto& d) { d["loads"] = {{{"block", 1}, {"force", {0, 0, -1}}, {"at", {0, 0, 0}}}}; },
       "loads[0].block: index 1 is out of range (1 blocks, 0-based)"},
      {[](auto& d) { d["loads"] = {{{"block", 0}, {"force", {0, 0}}, {"at", {0, 0, 0}}}}; },
       "loads[0].force: expected 3 finite numbers"},
      {[](auto& d) { d["loads"] = {{{"block", 0}, {"at", {0, 0, 0}}}}; },
       "loads[0]: missing field 'force'"},
  };
  for (const Case& c : cases) {
    nlohmann::json document = minimal_document();
    c.damage(document);
    const std::string message = load_error(document);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "' in: " << message;
  }
}

TEST(StructureJson, RejectsNonFiniteNumbers) {
  // JSON has no NaN or infinity literals; an overflowing literal is the way in.
  std::string text = minimal_document().dump();
  text.replace(text.find("[1,1,1]"), 7, "[1,-1e999,1]");
  try {
    structure_from_json(text, "huge.json");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_TRUE(std::string(e.what()).find("huge.json: not valid JSON: ") == 0) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e999"), std::string::npos) << e.what();
  }
}

TEST(StructureJson, RejectsTextThatIsNotJson) {
  try {
    structure_from_json("{\n  \"format\": \"ashlar-structure\",\n  oops\n}", "broken.json");
    FAIL();
  } catch (const IoError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("broken.json: not valid JSON: ", 0), 0u) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
  }
  EXPECT_THROW(structure_from_json("[1, 2]", "array.json"), IoError);
}

TEST(StructureJson, InvalidGeometryNamesTheBlock) {
  nlohmann::json document = minimal_document();
  // Reversing every face turns the cube inside out.
  for (auto& face : document["blocks"][0]["faces"]) {
    std::reverse(face.begin(), face.end());
  }
  try {
    structure_from_json(document.dump(), "inverted.json");
    FAIL();
  } catch (const GeometryError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("inverted.json: blocks[0] ('cube'): ", 0), 0u)
        << e.what();
  }
}

TEST(StructureJson, MissingFileNamesThePath) {
  try {
    load_structure("/nonexistent/ashlar/structure.json");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("'/nonexistent/ashlar/structure.json'"),
              std::string::npos);
  }
}

TEST(AtomicFile, WritesReplacesAndReads) {
  TempDir dir;
  const std::string path = dir.file("data.bin");
  const std::string binary("a\0b\nc\xff", 6);
  write_file_atomically(path, binary);
  EXPECT_EQ(read_file(path), binary);
  write_file_atomically(path, "second");
  EXPECT_EQ(read_file(path), "second");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"data.bin"});

  // Permissions are the usual ones for new files, not mkstemp's 0600.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  struct stat info {};
  ASSERT_EQ(::stat(path.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 0777, 0666 & ~mask);
}

TEST(AtomicFile, FailureNamesThePathAndLeavesNothing) {
  TempDir dir;
  try {
    write_file_atomically(dir.file("missing/folder/x.json"), "data");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("missing/folder/x.json")), std::string::npos);
  }
  // The target is a folder: the rename fails after the data was written.
  ASSERT_EQ(::mkdir(dir.file("taken").c_str(), 0755), 0);
  EXPECT_THROW(write_file_atomically(dir.file("taken"), "data"), IoError);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken"});
  ::rmdir(dir.file("taken").c_str());

  EXPECT_THROW(read_file(dir.file("absent")), IoError);
  EXPECT_THROW(read_file(dir.path()), IoError);
}
