#include "io/compas_assembly.hpp"

#include <cmath>
#include <map>

#include "analysis/equilibrium.hpp"
#include "geometry/block_builders.hpp"
#include "core/atomic_file.hpp"
#include "io/json_document.hpp"
#include "io/option_checks.hpp"

namespace ashlar {
namespace {

// The payload of a COMPAS-encoded object: "data" (compas 2) or "value"
// (compas 1) of {"dtype": ..., ...}; any other value as it is.
const json& payload(const json& value) {
  if (value.is_object() && value.contains("dtype")) {
    if (const auto data = value.find("data"); data != value.end()) return *data;
    if (const auto data = value.find("value"); data != value.end()) return *data;
  }
  return value;
}

// A node, vertex or face key as the file writes it: "3" for 3 and "3".
std::string key_text(const json& key) { return key.is_string() ? key.get<std::string>() : key.dump(); }

class AssemblyReader {
public:
  AssemblyReader(const std::string& path, const ImportOptions& options)
      : reader_(path), path_(path), options_(options) {}

  CompasAssembly read(const json& document) {
    const json& root = payload(document);
    if (document.is_object() && document.contains("dtype")) {
      out_.layout = document.contains("data") ? "compas 2" : "compas 1";
    }
    if (root.is_array()) {
      out_.layout = "list of meshes";
      for (size_t k = 0; k < root.size(); ++k) {
        add_block(payload(root[k]), std::to_string(k), "[" + std::to_string(k) + "]", false);
      }
      return std::move(out_);
    }
    reader_.expect_object(root, "top level");
    if (const auto graph = root.find("graph"); graph != root.end()) {
      if (out_.layout.empty()) out_.layout = "compas 2";
      read_graph(payload(*graph), "graph", nullptr);
    } else if (root.contains("assembly") && root.contains("blocks")) {
      out_.layout = "compas_assembly 0.x";
      const json& blocks = root["blocks"];
      reader_.expect_object(blocks, "blocks");
      read_graph(payload(root["assembly"]), "assembly", &blocks);
    } else {
      std::string keys;
      for (const auto& item : root.items()) keys += (keys.empty() ? "" : ", ") + item.key();
      reader_.fail("top level", "not a COMPAS Assembly: expected a \"graph\" (compas 1 and 2) or \"assembly\" and "
                                "\"blocks\" (compas_assembly 0.x), got the fields " + (keys.empty() ? "none" : keys));
    }
    return std::move(out_);
  }

private:
  void read_graph(const json& graph, const std::string& where, const json* blocks_by_key) {
    reader_.expect_object(graph, where);
    // compas graphs call them nodes; compas_assembly 0.x networks vertices.
    const char* nodes_name = graph.contains("node") ? "node" : "vertex";
    const json& nodes = reader_.member(graph, nodes_name, where);
    reader_.expect_object(nodes, where + "." + nodes_name);
    for (const auto& [key, attributes] : nodes.items()) {
      const std::string node_where = where + "." + nodes_name + "." + key;
      const json* mesh = nullptr;
      std::string mesh_where;
      if (attributes.is_object() && attributes.contains("block") && !attributes["block"].is_null()) {
        mesh = &payload(attributes["block"]);
        mesh_where = node_where + ".block";
      } else if (blocks_by_key && blocks_by_key->contains(key)) {
        mesh = &payload((*blocks_by_key)[key]);
        mesh_where = "blocks." + key;
      } else {
        reader_.fail(node_where, "the node has no block (a mesh under \"block\")");
      }
      bool support = false;
      if (attributes.is_object()) {
        if (const auto flag = attributes.find("is_support"); flag != attributes.end() && !flag->is_null()) {
          if (!flag->is_boolean()) reader_.fail(node_where + ".is_support", "expected true or false, got " + flag->dump());
          support = flag->get<bool>();
        }
      }
      node_index_[key] = static_cast<int>(out_.blocks.size());
      add_block(*mesh, key, mesh_where, support);
    }
    const auto edges = graph.find("edge");
    if (edges == graph.end() || edges->is_null()) return;
    reader_.expect_object(*edges, where + ".edge");
    for (const auto& [u, neighbours] : edges->items()) {
      if (neighbours.is_null()) continue;
      reader_.expect_object(neighbours, where + ".edge." + u);
      for (const auto& [v, attributes] : neighbours.items()) {
        const std::string edge_where = where + ".edge." + u + "." + v;
        if (attributes.is_object()) read_edge(attributes, node(u, edge_where), node(v, edge_where), edge_where);
      }
    }
  }

  int node(const std::string& key, const std::string& where) const {
    const auto found = node_index_.find(key);
    if (found == node_index_.end()) reader_.fail(where, "node " + key + " does not exist");
    return found->second;
  }

  void add_block(const json& mesh, const std::string& key, const std::string& where, bool support) {
    reader_.expect_object(mesh, where);
    const json& vertex = reader_.member(mesh, "vertex", where);
    const json& face = reader_.member(mesh, "face", where);
    reader_.expect_object(vertex, where + ".vertex");
    reader_.expect_object(face, where + ".face");
    // Coordinates a vertex leaves out take the mesh's defaults (compas 2
    // "default_vertex_attributes", compas 1 "dva").
    Vec3 defaults = Vec3::Zero();
    for (const char* name : {"default_vertex_attributes", "dva"}) {
      const auto found = mesh.find(name);
      if (found == mesh.end() || !found->is_object()) continue;
      for (int axis = 0; axis < 3; ++axis) {
        const char* coordinate = axis == 0 ? "x" : axis == 1 ? "y" : "z";
        if (const auto value = found->find(coordinate); value != found->end() && value->is_number()) {
          defaults[axis] = value->get<double>();
        }
      }
    }
    std::vector<Vec3> vertices;
    std::vector<std::string> vertex_keys, face_keys;
    std::map<std::string, int> vertex_index;
    for (const auto& [vertex_key, attributes] : vertex.items()) {
      const std::string vertex_where = where + ".vertex." + vertex_key;
      reader_.expect_object(attributes, vertex_where);
      Vec3 p = defaults;
      for (int axis = 0; axis < 3; ++axis) {
        const char* coordinate = axis == 0 ? "x" : axis == 1 ? "y" : "z";
        if (const auto value = attributes.find(coordinate); value != attributes.end()) {
          p[axis] = reader_.number(*value, vertex_where + "." + coordinate);
        }
      }
      vertex_index[vertex_key] = static_cast<int>(vertices.size());
      vertex_keys.push_back(vertex_key);
      vertices.push_back(p);
    }
    std::vector<FaceLoop> faces;
    for (const auto& [face_key, loop] : face.items()) {
      const std::string face_where = where + ".face." + face_key;
      reader_.expect_array(loop, face_where);
      FaceLoop indices;
      for (size_t k = 0; k < loop.size(); ++k) {
        const auto found = vertex_index.find(key_text(loop[k]));
        if (found == vertex_index.end()) {
          reader_.fail(face_where + "[" + std::to_string(k) + "]", "vertex " + loop[k].dump() + " does not exist");
        }
        indices.push_back(found->second);
      }
      faces.push_back(std::move(indices));
      face_keys.push_back(face_key);
    }
    std::string name = "node " + key;
    if (const auto attributes = mesh.find("attributes"); attributes != mesh.end() && attributes->is_object()) {
      if (const auto given = attributes->find("name"); given != attributes->end() && given->is_string()) {
        const std::string text = given->get<std::string>();
        if (!text.empty() && text != "Block" && text != "Mesh") name = text;
      }
    }
    Box3 bounds;
    for (const Vec3& p : vertices) bounds.add(p);
    const double weld = bounds.empty() ? 0.0 : options_.relative_weld_tolerance * bounds.diagonal();
    const BlockStyle style{options_.density, name, options_.planarity};
    // Named by their keys, as the paths in messages are ("blocks.0.face.2").
    MeshNumbering numbering;
    numbering.vertex_name = [&vertex_keys](int index) { return "vertex " + vertex_keys[index]; };
    numbering.face_name = [&face_keys](int index) { return "face " + face_keys[index]; };
    try {
      out_.blocks.push_back(import_object(name, vertices, faces, weld, style,
                                          path_ + ": " + where + " ('" + name + "')", numbering));
    } catch (const GeometryError& error) {
      throw GeometryError(error.what() + std::string(" (vertices and faces by their keys in the file)"));
    }
    out_.supports.push_back(support);
  }

  Vec3 point(const json& value, const std::string& where) const { return reader_.vec3(payload(value), where); }

  void read_edge(const json& attributes, int a, int b, const std::string& where) {
    // compas_assembly 0.x: one interface as flat edge attributes.
    if (const auto points = attributes.find("interface_points"); points != attributes.end() && !points->is_null()) {
      CompasAssembly::StoredInterface contact{a, b, polygon(*points, where + ".interface_points"), std::nullopt,
                                              path_ + ": " + where};
      if (const auto uvw = attributes.find("interface_uvw"); uvw != attributes.end() && !uvw->is_null()) {
        reader_.expect_array(*uvw, where + ".interface_uvw");
        if (uvw->size() != 3) reader_.fail(where + ".interface_uvw", "expected the 3 axes u, v, w");
        contact.normal = point((*uvw)[2], where + ".interface_uvw[2]");
      }
      out_.interfaces.push_back(std::move(contact));
      return;
    }
    // compas 1 and 2: a list of Interface objects ("interface": a single one).
    std::vector<std::pair<const json*, std::string>> listed;
    if (const auto many = attributes.find("interfaces"); many != attributes.end() && !many->is_null()) {
      reader_.expect_array(*many, where + ".interfaces");
      for (size_t k = 0; k < many->size(); ++k) {
        listed.emplace_back(&(*many)[k], where + ".interfaces[" + std::to_string(k) + "]");
      }
    } else if (const auto one = attributes.find("interface"); one != attributes.end() && !one->is_null()) {
      listed.emplace_back(&*one, where + ".interface");
    }
    for (const auto& [entry, entry_where] : listed) {
      const json& data = payload(*entry);
      reader_.expect_object(data, entry_where);
      CompasAssembly::StoredInterface contact{
          a, b, polygon(reader_.member(data, "points", entry_where), entry_where + ".points"), std::nullopt,
          path_ + ": " + entry_where};
      if (const auto frame = data.find("frame"); frame != data.end() && !frame->is_null()) {
        const json& axes = payload(*frame);
        reader_.expect_object(axes, entry_where + ".frame");
        const Vec3 x = point(reader_.member(axes, "xaxis", entry_where + ".frame"), entry_where + ".frame.xaxis");
        const Vec3 y = point(reader_.member(axes, "yaxis", entry_where + ".frame"), entry_where + ".frame.yaxis");
        const Vec3 z = x.cross(y);
        if (!(z.norm() > 1e-12 * x.norm() * y.norm())) {
          reader_.fail(entry_where + ".frame", "its xaxis and yaxis are parallel or zero");
        }
        contact.normal = z;
      }
      out_.interfaces.push_back(std::move(contact));
    }
  }

  std::vector<Vec3> polygon(const json& points, const std::string& where) const {
    reader_.expect_array(points, where);
    std::vector<Vec3> out;
    for (size_t k = 0; k < points.size(); ++k) out.push_back(point(points[k], where + "[" + std::to_string(k) + "]"));
    return out;
  }

  JsonReader reader_;
  std::string path_;
  const ImportOptions& options_;
  std::map<std::string, int> node_index_;
  CompasAssembly out_;
};

// Appends a member whose key the object does not have yet: ordered_json's
// operator[] searches every key first, which made the nodes and edges of a
// large assembly quadratic to build.
json& append_member(json& object, std::string key, json value) {
  return object.get_ref<json::object_t&>().emplace_back(std::move(key), std::move(value)).second;
}

json mesh_json(const Structure& structure, int i) {
  const Block& block = structure.block(i);
  json vertex = json::object();
  for (size_t k = 0; k < block.vertices().size(); ++k) {
    const Vec3& p = block.vertices()[k];
    append_member(vertex, std::to_string(k), {{"x", p.x()}, {"y", p.y()}, {"z", p.z()}});
  }
  json face = json::object(), facedata = json::object();
  for (size_t f = 0; f < block.faces().size(); ++f) {
    append_member(face, std::to_string(f), block.faces()[f]);
    append_member(facedata, std::to_string(f), json::object());
  }
  json data;
  data["attributes"] = {{"name", structure.name(i)}, {"node", i}};
  data["default_vertex_attributes"] = {{"x", 0.0}, {"y", 0.0}, {"z", 0.0}};
  data["default_edge_attributes"] = json::object();
  data["default_face_attributes"] = json::object();
  data["vertex"] = std::move(vertex);
  data["face"] = std::move(face);
  data["facedata"] = std::move(facedata);
  data["edgedata"] = json::object();
  data["max_vertex"] = static_cast<int>(block.vertices().size()) - 1;
  data["max_face"] = static_cast<int>(block.faces().size()) - 1;
  return {{"dtype", "compas_assembly.datastructures/Block"}, {"data", std::move(data)}};
}

}  // namespace

CompasAssembly read_compas_assembly(const std::string& path, const ImportOptions& options) {
  const std::string text = read_file(path);
  const JsonReader reader(path);
  CompasAssembly assembly =
      read_json_document(text, reader, [&](const json& root) { return AssemblyReader(path, options).read(root); });
  face_plates_to_blocks(assembly.blocks);
  return assembly;
}

Structure compas_structure(CompasAssembly assembly, bool stored_interfaces,
                           const std::function<bool(const ImportedBlock&)>& also_support) {
  Structure structure;
  for (size_t i = 0; i < assembly.blocks.size(); ++i) {
    const bool support = assembly.supports[i] || !assembly.blocks[i].surface.empty() ||
                         (also_support && also_support(assembly.blocks[i]));
    // A repeated name gets the block's index appended (Structure::add).
    const std::string& name = assembly.blocks[i].name;
    structure.add(std::make_shared<const Block>(std::move(assembly.blocks[i].block)), support,
                  structure.find(name) >= 0 ? std::string() : name);
  }
  if (!stored_interfaces) return structure;
  for (const CompasAssembly::StoredInterface& contact : assembly.interfaces) {
    try {
      structure.add_interface(contact.a, contact.b, {contact.points}, contact.normal);
    } catch (const InvalidArgument& e) {
      throw IoError(contact.where + ": " + e.what());
    }
  }
  return structure;
}

std::string compas_assembly_json(const Structure& structure, const CompasExportOptions& options) {
  if (structure.size() == 0) throw InvalidArgument("export: the structure has no blocks");
  check_result_of_structure(structure, options.result, false, false, options.contact, "export");
  for (int i = 0; i < structure.size(); ++i) {
    if (!is_valid_utf8(json(structure.name(i)))) {
      throw InvalidArgument("export: the name of block " + std::to_string(i + 1) + " is not valid UTF-8 text");
    }
  }
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(options.contact);
  const std::vector<Interface>& interfaces = *interfaces_list;
  // Each interface's vertex forces in the result, in its vertices' order.
  std::vector<std::vector<int>> forces_of(interfaces.size());
  if (options.result) {
    const EquilibriumResult& r = *options.result;
    for (size_t k = 0; k < r.vertex_interface.size(); ++k) forces_of[r.vertex_interface[k]].push_back(static_cast<int>(k));
  }
  json nodes = json::object();
  for (int i = 0; i < structure.size(); ++i) {
    append_member(nodes, std::to_string(i), {{"block", mesh_json(structure, i)}, {"is_support", structure.is_support(i)}});
  }
  // Interfaces come sorted by (a, b): each edge's entries are appended in turn.
  json edges = json::object();
  json* neighbours = nullptr;
  json* pair = nullptr;
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const Interface& contact = interfaces[k];
    json points = json::array();
    for (const Vec3& p : contact.vertices) points.push_back(vec3_to_json(p));
    json forces = nullptr;
    if (options.result) {
      forces = json::array();
      const std::vector<int>& at = forces_of[k];
      for (size_t j = 0; j < contact.vertices.size(); ++j) {
        // Interfaces between supports carry no unknowns: zero forces.
        const Eigen::Vector4d f = at.empty() ? Eigen::Vector4d::Zero() : options.result->vertex_forces[at.at(j)];
        forces.push_back({{"c_np", f(0)}, {"c_nn", f(1)}, {"c_u", f(2)}, {"c_v", f(3)}});
      }
    }
    json frame = {{"dtype", "compas.geometry/Frame"},
                  {"data", {{"point", vec3_to_json(contact.center)}, {"xaxis", vec3_to_json(contact.u)},
                            {"yaxis", vec3_to_json(contact.v)}}}};
    json entry = {{"dtype", "compas_assembly.datastructures/Interface"},
                  {"data", {{"points", std::move(points)}, {"size", contact.area}, {"frame", std::move(frame)},
                            {"forces", std::move(forces)}, {"mesh", nullptr}}}};
    if (k == 0 || contact.a != interfaces[k - 1].a) {
      neighbours = &append_member(edges, std::to_string(contact.a), json::object());
    }
    if (k == 0 || contact.a != interfaces[k - 1].a || contact.b != interfaces[k - 1].b) {
      pair = &append_member(*neighbours, std::to_string(contact.b), {{"interfaces", json::array()}});
    }
    (*pair)["interfaces"].push_back(std::move(entry));
  }
  json graph;
  graph["attributes"] = json::object();
  graph["default_node_attributes"] = {{"block", nullptr}, {"is_support", false}, {"section", nullptr},
                                      {"mesh_size", nullptr}, {"displacement", {0, 0, 0, 0, 0, 0}}};
  graph["default_edge_attributes"] = {{"interfaces", nullptr}};
  graph["node"] = std::move(nodes);
  graph["edge"] = std::move(edges);
  graph["max_node"] = structure.size() - 1;
  json attributes = {{"name", "Assembly"},
                     {"units", {{"length", "m"}, {"force", "N"}}}};
  if (options.result) {
    attributes["ashlar_result"] = {{"stable", options.result->stable},
                                   {"status", status_name(options.result->status)},
                                   {"infeasibility", std::isfinite(options.result->infeasibility)
                                                         ? json(options.result->infeasibility)
                                                         : json(nullptr)}};
  }
  json root = {{"dtype", "compas_assembly.datastructures/Assembly"},
               {"data", {{"attributes", std::move(attributes)},
                         {"graph", {{"dtype", "compas.datastructures/Graph"}, {"data", std::move(graph)}}}}}};
  return pretty_json(root);
}

void write_compas_assembly(const Structure& structure, const std::string& path, const CompasExportOptions& options) {
  write_file_atomically(path, compas_assembly_json(structure, options));
}

}  // namespace ashlar
