// The structure file format (docs/structure-format.md) with nlohmann_json.
// Doubles are written in nlohmann's shortest round-trip form and read back
// with correct rounding, so a save/load cycle reproduces every coordinate
// bit for bit. Reading is strict: every defect is reported with the path of
// the offending entry, e.g. "blocks[3].vertices[2]: expected 3 finite numbers".
#include "io/structure_json.hpp"

#include <cmath>
#include <memory>
#include <optional>

#include "core/error.hpp"
#include "core/atomic_file.hpp"
#include "io/json_document.hpp"

namespace ashlar {
namespace {

constexpr const char* kFormatName = "ashlar-structure";

void check_header(const JsonReader& reader, const json& root) {
  const json& format = reader.member(root, "format", "");
  if (!format.is_string() || format.get<std::string>() != kFormatName) {
    reader.fail("format", "not an ashlar structure file (format is " + format.dump() +
                              ", expected \"" + kFormatName + "\")");
  }
  const json& version = reader.member(root, "version", "");
  if (!version.is_number_integer() || version.get<std::int64_t>() != kStructureFormatVersion) {
    reader.fail("version", "unsupported version " + version.dump() + " (this build reads version " +
                               std::to_string(kStructureFormatVersion) + ")");
  }
  const auto units = root.find("units");
  if (units == root.end()) return;
  reader.expect_object(*units, "units");
  reader.reject_unknown_keys(*units, {"length", "mass", "force"}, "units");
  const std::pair<const char*, const char*> supported[] = {
      {"length", "m"}, {"mass", "kg"}, {"force", "N"}};
  for (const auto& [quantity, unit] : supported) {
    const auto given = units->find(quantity);
    if (given != units->end() && *given != unit) {
      reader.fail(std::string("units.") + quantity,
                  "unsupported unit " + given->dump() + " (only \"" + unit + "\" is supported)");
    }
  }
}

// planarity: accepted warp of faces (see Block) for blocks that do not
// carry a larger one of their own.
void read_block(const JsonReader& reader, const json& entry, int i, double planarity, Structure& structure) {
  const std::string where = "blocks[" + std::to_string(i) + "]";
  reader.expect_object(entry, where);
  reader.reject_unknown_keys(entry, {"name", "support", "density", "planarity", "vertices", "faces"}, where);

  std::string name;
  if (const auto found = entry.find("name"); found != entry.end()) {
    if (!found->is_string()) reader.fail(where + ".name", "expected a string");
    name = found->get<std::string>();
  }
  bool support = false;
  if (const auto found = entry.find("support"); found != entry.end()) {
    if (!found->is_boolean()) reader.fail(where + ".support", "expected true or false");
    support = found->get<bool>();
  }
  double density = kDefaultDensity;
  if (const auto found = entry.find("density"); found != entry.end()) {
    density = reader.number(*found, where + ".density");
    if (density <= 0) reader.fail(where + ".density", "must be positive (kg/m^3)");
  }
  if (const auto found = entry.find("planarity"); found != entry.end()) {
    planarity = std::max(planarity, reader.number(*found, where + ".planarity"));
  }

  const json& vertex_list = reader.member(entry, "vertices", where);
  reader.expect_array(vertex_list, where + ".vertices");
  std::vector<Vec3> vertices;
  vertices.reserve(vertex_list.size());
  for (size_t v = 0; v < vertex_list.size(); ++v) {
    vertices.push_back(
        reader.vec3(vertex_list[v], where + ".vertices[" + std::to_string(v) + "]"));
  }

  const json& face_list = reader.member(entry, "faces", where);
  reader.expect_array(face_list, where + ".faces");
  std::vector<FaceLoop> faces;
  faces.reserve(face_list.size());
  for (size_t f = 0; f < face_list.size(); ++f) {
    const std::string face_where = where + ".faces[" + std::to_string(f) + "]";
    reader.expect_array(face_list[f], face_where);
    FaceLoop loop;
    for (size_t k = 0; k < face_list[f].size(); ++k) {
      loop.push_back(reader.index(face_list[f][k], vertices.size(), "vertices",
                                  face_where + "[" + std::to_string(k) + "]"));
    }
    faces.push_back(std::move(loop));
  }

  const std::string label = where + (name.empty() ? "" : " ('" + name + "')");
  // Vertices and faces named as the file's paths name them (0-based).
  MeshNumbering numbering;
  numbering.vertex_name = [](int index) { return "vertices[" + std::to_string(index) + "]"; };
  numbering.face_name = [](int index) { return "faces[" + std::to_string(index) + "]"; };
  BlockPtr block;
  try {
    block = std::make_shared<const Block>(std::move(vertices), std::move(faces), density, name, planarity,
                                          numbering);
  } catch (const InvalidArgument& e) {
    reader.fail(where + ".planarity", e.what());
  } catch (const GeometryError& e) {
    throw GeometryError(reader.source() + ": " + label + ": " + e.what());
  }
  try {
    structure.add(std::move(block), support, name);
  } catch (const InvalidArgument& e) {
    reader.fail(label, e.what());
  }
}

void read_load(const JsonReader& reader, const json& entry, int i, Structure& structure) {
  const std::string where = "loads[" + std::to_string(i) + "]";
  reader.expect_object(entry, where);
  reader.reject_unknown_keys(entry, {"block", "force", "at"}, where);
  PointLoad load;
  load.block = reader.index(reader.member(entry, "block", where), structure.size(), "blocks",
                            where + ".block");
  load.force = reader.vec3(reader.member(entry, "force", where), where + ".force");
  load.at = reader.vec3(reader.member(entry, "at", where), where + ".at");
  try {
    structure.add_load(load);
  } catch (const InvalidArgument& e) {
    reader.fail(where, e.what());
  }
}

CableEnd read_cable_end(const JsonReader& reader, const json& entry, const std::string& where,
                        const Structure& structure) {
  reader.expect_object(entry, where);
  reader.reject_unknown_keys(entry, {"block", "point"}, where);
  CableEnd end;
  if (const auto block = entry.find("block"); block != entry.end()) {
    end.block = reader.index(*block, structure.size(), "blocks", where + ".block");
  }
  end.point = reader.vec3(reader.member(entry, "point", where), where + ".point");
  return end;
}

void read_cable(const JsonReader& reader, const json& entry, int i, Structure& structure) {
  const std::string where = "cables[" + std::to_string(i) + "]";
  reader.expect_object(entry, where);
  reader.reject_unknown_keys(entry, {"from", "to", "mass_per_length", "max_tension"}, where);
  Cable cable;
  cable.from = read_cable_end(reader, reader.member(entry, "from", where), where + ".from", structure);
  cable.to = read_cable_end(reader, reader.member(entry, "to", where), where + ".to", structure);
  if (const auto mass = entry.find("mass_per_length"); mass != entry.end()) {
    cable.mass_per_length = reader.number(*mass, where + ".mass_per_length");
  }
  if (const auto bound = entry.find("max_tension"); bound != entry.end()) {
    cable.max_tension = reader.number(*bound, where + ".max_tension");
  }
  try {
    structure.add_cable(cable);
  } catch (const InvalidArgument& e) {
    reader.fail(where, e.what());
  }
}

void read_interface(const JsonReader& reader, const json& entry, int i, Structure& structure) {
  const std::string where = "interfaces[" + std::to_string(i) + "]";
  reader.expect_object(entry, where);
  reader.reject_unknown_keys(entry, {"a", "b", "normal", "polygon"}, where);
  const int a = reader.index(reader.member(entry, "a", where), structure.size(), "blocks", where + ".a");
  const int b = reader.index(reader.member(entry, "b", where), structure.size(), "blocks", where + ".b");
  std::optional<Vec3> normal;
  if (const auto found = entry.find("normal"); found != entry.end()) normal = reader.vec3(*found, where + ".normal");
  const json& points = reader.member(entry, "polygon", where);
  reader.expect_array(points, where + ".polygon");
  std::vector<Vec3> polygon;
  for (size_t k = 0; k < points.size(); ++k) {
    polygon.push_back(reader.vec3(points[k], where + ".polygon[" + std::to_string(k) + "]"));
  }
  try {
    structure.add_interface(a, b, {polygon}, normal);
  } catch (const InvalidArgument& e) {
    reader.fail(where, e.what());
  }
}

json cable_end_to_json(const CableEnd& end) {
  json out;
  if (end.block >= 0) out["block"] = end.block;
  out["point"] = vec3_to_json(end.point);
  return out;
}

Structure read_document(const JsonReader& reader, const json& root, double planarity) {
  reader.expect_object(root, "top level");
  // Format and version first: a file of another kind or a later version is
  // reported as such, not by its first unknown field.
  check_header(reader, root);
  reader.reject_unknown_keys(root,
                             {"format", "version", "units", "planar", "blocks", "loads", "cables", "interfaces"},
                             "top level");

  Structure structure;
  if (const auto planar = root.find("planar"); planar != root.end()) {
    if (!planar->is_boolean()) reader.fail("planar", "expected true or false");
    structure.set_planar(planar->get<bool>());
  }
  const json& blocks = reader.member(root, "blocks", "");
  reader.expect_array(blocks, "blocks");
  for (size_t i = 0; i < blocks.size(); ++i) {
    read_block(reader, blocks[i], static_cast<int>(i), planarity, structure);
  }
  if (const auto loads = root.find("loads"); loads != root.end()) {
    reader.expect_array(*loads, "loads");
    for (size_t i = 0; i < loads->size(); ++i) {
      read_load(reader, (*loads)[i], static_cast<int>(i), structure);
    }
  }
  if (const auto cables = root.find("cables"); cables != root.end()) {
    reader.expect_array(*cables, "cables");
    for (size_t i = 0; i < cables->size(); ++i) {
      read_cable(reader, (*cables)[i], static_cast<int>(i), structure);
    }
  }
  if (const auto interfaces = root.find("interfaces"); interfaces != root.end()) {
    reader.expect_array(*interfaces, "interfaces");
    for (size_t i = 0; i < interfaces->size(); ++i) {
      read_interface(reader, (*interfaces)[i], static_cast<int>(i), structure);
    }
  }
  return structure;
}

}  // namespace

std::string structure_to_json(const Structure& structure) {
  json blocks = json::array();
  for (int i = 0; i < structure.size(); ++i) {
    const Block& block = structure.block(i);
    json vertices = json::array();
    for (const Vec3& v : block.vertices()) vertices.push_back(vec3_to_json(v));
    json faces = json::array();
    for (const FaceLoop& loop : block.faces()) faces.push_back(loop);
    json entry;
    entry["name"] = structure.name(i);
    if (!is_valid_utf8(entry["name"])) {
      throw InvalidArgument("cannot save the structure: the name of block " +
                            std::to_string(i + 1) + " is not valid UTF-8 text");
    }
    entry["support"] = structure.is_support(i);
    entry["density"] = block.density();
    if (block.planarity() > 0.0) entry["planarity"] = block.planarity();
    entry["vertices"] = std::move(vertices);
    entry["faces"] = std::move(faces);
    blocks.push_back(std::move(entry));
  }
  json loads = json::array();
  for (const PointLoad& load : structure.loads()) {
    json entry;
    entry["block"] = load.block;
    entry["force"] = vec3_to_json(load.force);
    entry["at"] = vec3_to_json(load.at);
    loads.push_back(std::move(entry));
  }
  json cables = json::array();
  for (const Cable& cable : structure.cables()) {
    json entry;
    entry["from"] = cable_end_to_json(cable.from);
    entry["to"] = cable_end_to_json(cable.to);
    entry["mass_per_length"] = cable.mass_per_length;
    if (std::isfinite(cable.max_tension)) entry["max_tension"] = cable.max_tension;
    cables.push_back(std::move(entry));
  }
  json interfaces = json::array();
  for (const Interface& contact : structure.explicit_interfaces()) {
    json polygon = json::array();
    for (const Vec3& p : contact.vertices) polygon.push_back(vec3_to_json(p));
    json entry;
    entry["a"] = contact.a;
    entry["b"] = contact.b;
    entry["normal"] = vec3_to_json(contact.normal);
    entry["polygon"] = std::move(polygon);
    interfaces.push_back(std::move(entry));
  }
  json root;
  root["format"] = kFormatName;
  root["version"] = kStructureFormatVersion;
  root["units"] = {{"length", "m"}, {"mass", "kg"}, {"force", "N"}};
  if (structure.planar()) root["planar"] = true;
  root["blocks"] = std::move(blocks);
  root["loads"] = std::move(loads);
  if (!cables.empty()) root["cables"] = std::move(cables);
  if (!interfaces.empty()) root["interfaces"] = std::move(interfaces);
  return pretty_json(root);
}

Structure structure_from_json(const std::string& text, const std::string& source_name, double planarity) {
  const JsonReader reader(source_name);
  return read_json_document(text, reader, [&](const json& root) { return read_document(reader, root, planarity); });
}

void save_structure(const Structure& structure, const std::string& path) {
  write_file_atomically(path, structure_to_json(structure));
}

Structure load_structure(const std::string& path, double planarity) {
  return structure_from_json(read_file(path), path, planarity);
}

}  // namespace ashlar
