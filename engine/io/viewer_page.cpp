// The HTML viewer's page: the scene as JSON, the scripts as JSON strings
// (exactly what the browser gets back, whatever characters they hold), both
// in <script type="application/json"> elements of web/viewer.html, every
// "<" written \u003c so that nothing in them can close the element.
#include "io/viewer_page.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "analysis/equilibrium.hpp"
#include "analysis/mechanism.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "io/color_map.hpp"
#include "io/force_glyphs.hpp"
#include "io/json_document.hpp"
#include "io/simulation_export.hpp"
#include "io/structure_scene.hpp"
#include "io/web_assets.hpp"

namespace ashlar {
namespace {

// Colour stops of the legend's bar, sampled from the map itself.
constexpr int kLegendStops = 33;
// Read-outs carry 4 significant digits.
constexpr int kReadoutDigits = 4;

std::string readout(double value) { return message_number(value, kReadoutDigits); }

// A force in N, kN or MN, whichever keeps it readable.
std::string force(double newtons) {
  const double size = std::abs(newtons);
  if (size >= 1e6) return readout(newtons / 1e6) + " MN";
  if (size >= 1e3) return readout(newtons / 1e3) + " kN";
  return readout(newtons) + " N";
}

std::string point(const Vec3& p) {
  return "(" + readout(p.x()) + ", " + readout(p.y()) + ", " + readout(p.z()) + ") m";
}

// Coordinates are written rounded to a millionth of the structure's size
// (the diagonal of its bounding box), at a power of ten: the few decimals a
// picture needs (far finer than a pixel) instead of the 17 digits of a
// single-precision number printed as a double.
class Rounding {
 public:
  explicit Rounding(double size) : scale_(std::pow(10.0, 6.0 - std::floor(std::log10(size > 0.0 ? size : 1.0)))) {}
  double operator()(double value) const { return std::round(value * scale_) / scale_; }

 private:
  double scale_;  // 10^decimals
};

using Rows = std::vector<std::pair<std::string, std::string>>;

Rows block_rows(const Structure& structure, int i, const ExportOptions& options) {
  Rows rows{{"block", std::to_string(i + 1) + " of " + std::to_string(structure.size())},
            {"kind", structure.is_support(i) ? "support" : "free block"},
            {"mass", readout(structure.block(i).mass()) + " kg"}};
  if (options.color_scale) {
    const std::string& label = options.color_scale->label;
    rows.emplace_back(label.empty() ? "value" : label, readout(options.color_scale->values[i]));
  }
  // A stable structure's tension is solver round-off.
  const EquilibriumResult* result = options.result;
  if (result && !result->stable && static_cast<int>(result->block_tension.size()) == structure.size()) {
    rows.emplace_back("tension on its interfaces", force(result->block_tension[i]));
  }
  return rows;
}

Rows interface_rows(const Structure& structure, int k, const ExportOptions& options) {
  const std::shared_ptr<const std::vector<Interface>> interfaces = structure.interfaces(options.contact);
  const Interface& contact = interfaces->at(k);
  Rows rows{{"between", structure.name(contact.a) + " and " + structure.name(contact.b)},
            {"area", readout(contact.area) + " m²"}};
  if (const EquilibriumResult* result = options.result) {
    const InterfaceForces& f = result->interfaces.at(k);
    rows.emplace_back("normal force",
                      force(f.normal_force) + (f.normal_force >= 0 ? " (compression)" : " (tension)"));
    if (!result->stable) rows.emplace_back("tension", force(f.tension));
    const ArrowForce drawn = arrow_force(structure, contact, f);
    rows.emplace_back("resultant", force(drawn.force.norm()) + " on " + structure.name(drawn.on) + " by " +
                                       structure.name(drawn.by));
    rows.emplace_back("its components", "(" + readout(drawn.force.x()) + ", " + readout(drawn.force.y()) + ", " +
                                            readout(drawn.force.z()) + ") N");
    rows.emplace_back("centre of pressure", point(f.center_of_pressure));
  }
  return rows;
}

// A vertex's arrow: what it draws, then its joint's rows.
Rows vertex_arrow_rows(const Structure& structure, const SceneObject& object, const ExportOptions& options) {
  const Vec3& f = object.arrow->force;
  const bool friction = object.name.rfind("friction ", 0) == 0;
  Rows rows{{friction ? "friction at the vertex" : "normal force at the vertex", force(f.norm())},
            {"its components", "(" + readout(f.x()) + ", " + readout(f.y()) + ", " + readout(f.z()) + ") N"},
            {"vertex", point(object.arrow->tail)}};
  const Rows joint = interface_rows(structure, object.interface, options);
  rows.insert(rows.end(), joint.begin(), joint.end());
  return rows;
}

Rows thrust_rows(const SceneObject& object) {
  if (object.tubes.empty()) return {{"what", "the line of thrust: centres of pressure joined through each block"}};
  double thickest = 0.0;
  for (const TubeSegment& tube : object.tubes) thickest = std::max(thickest, tube.radius);
  return {{"what", "the thrust network: from each block's centroid to the centres of pressure of its joints in "
                   "compression, along the load paths"},
          {"thickness", "cross-section in proportion to the joint's resultant; the largest has radius " +
                            readout(thickest) + " m"}};
}

Rows object_rows(const Structure& structure, const SceneObject& object, const ExportOptions& options) {
  switch (object.layer) {
    case SceneLayer::blocks: return block_rows(structure, object.block, options);
    case SceneLayer::forces:
      if (options.force_mode == ForceMode::vertices) return vertex_arrow_rows(structure, object, options);
      return interface_rows(structure, object.interface, options);
    case SceneLayer::interfaces: return interface_rows(structure, object.interface, options);
    case SceneLayer::thrust: return thrust_rows(object);
    case SceneLayer::traces: return {{"what", "paths of the loads down to the supports"}};
    case SceneLayer::limit: {
      // "hinge a-b", "sliding a-b" or "separation a-b", over the joint's own rows.
      const std::string kind = object.name.substr(0, object.name.find(' '));
      Rows rows{{"what", kind == "hinge"     ? "a hinge of the collapse mechanism"
                         : kind == "sliding" ? "a joint that slides in the collapse mechanism"
                                             : "a joint that separates in the collapse mechanism"}};
      const Rows joint = interface_rows(structure, object.interface, options);
      rows.insert(rows.end(), joint.begin(), joint.end());
      return rows;
    }
    case SceneLayer::cables:
    case SceneLayer::edges: break;
  }
  return {};
}

json color_json(const Rgb& c) { return json::array({c.r, c.g, c.b, c.a}); }

json object_json(const Structure& structure, const SceneObject& object, const ExportOptions& options,
                 const Rounding& rounded) {
  json info = json::array();
  for (const auto& [key, value] : object_rows(structure, object, options)) info.push_back({key, value});
  json item = {{"layer", kSceneLayerNames.name(object.layer)},
               {"name", object.name},
               {"color", color_json(object.color)},
               {"two_sided", object.two_sided},
               {"info", std::move(info)}};
  if (const std::optional<ArrowGlyph>& arrow = object.arrow) {
    // Arrows are many and alike: the page builds each from its ends and
    // proportions, as arrow_faces does, rather than holding its facets.
    json values = json::array();
    for (const Vec3& p : {arrow->tail, arrow->tip}) {
      for (int axis = 0; axis < 3; ++axis) values.push_back(rounded(p[axis]));
    }
    for (double size : {arrow->shape.shaft_radius, arrow->shape.head_radius, arrow->shape.head_length}) {
      values.push_back(rounded(size));
    }
    values.push_back(arrow->shape.sides);
    item["arrow"] = std::move(values);
    return item;
  }
  if (!object.tubes.empty()) {
    // Likewise the thrust network's tubes: ends and radius each.
    json values = json::array();
    for (const TubeSegment& tube : object.tubes) {
      for (const Vec3& p : {tube.from, tube.to}) {
        for (int axis = 0; axis < 3; ++axis) values.push_back(rounded(p[axis]));
      }
      values.push_back(rounded(tube.radius));
    }
    item["tubes"] = std::move(values);
    return item;
  }
  json positions = json::array(), triangles = json::array();
  for (const Vec3& p : object.mesh.positions) {
    for (int axis = 0; axis < 3; ++axis) positions.push_back(rounded(p[axis]));
  }
  for (const auto& triangle : object.mesh.triangles) {
    for (unsigned index : triangle) triangles.push_back(index);
  }
  item["positions"] = std::move(positions);
  item["triangles"] = std::move(triangles);
  return item;
}

std::string summary(const Structure& structure, const ExportOptions& options) {
  std::string text = std::to_string(structure.size()) + " blocks";
  if (const EquilibriumResult* result = options.result) {
    // A load factor's result is the equilibrium at the factor: at its limit,
    // where "stable" would read as a verdict on the structure as loaded.
    if (options.load_factor) {
      text += ": at its limit, load factor " + readout(*options.load_factor);
    } else {
      text += result->stable ? ": stable" : ": unstable, infeasibility " + readout(result->infeasibility);
    }
    text += std::string(" (") + kAnalysisMethodNames.name(result->method) + " method, solver " +
            kSolverStatusNames.name(result->status) + ")";
  }
  return text;
}

// The page's key: what each colour drawn means, for the objects present.
json key_json(const ExportOptions& options, const std::vector<SceneObject>& objects, const bool present[]) {
  json key = json::array();
  const auto add = [&](const std::string& label, const Rgb& c) { key.push_back({{"label", label}, {"color", {c.r, c.g, c.b}}}); };
  if (present[static_cast<int>(SceneLayer::forces)]) {
    add("compression", options.compression_color);
    add("tension", options.tension_color);
    const auto friction = [](const SceneObject& o) { return o.layer == SceneLayer::forces && o.name.rfind("friction ", 0) == 0; };
    if (std::any_of(objects.begin(), objects.end(), friction)) add("friction", options.friction_color);
  }
  if (present[static_cast<int>(SceneLayer::interfaces)]) add("contact interfaces", options.interface_color);
  for (const SceneObject& object : objects) {
    if (object.layer != SceneLayer::thrust) continue;
    add(object.tubes.empty() ? "thrust line" : "thrust network (thickness: force)", options.thrust_color);
  }
  if (present[static_cast<int>(SceneLayer::cables)]) add("cables", options.cable_color);
  if (present[static_cast<int>(SceneLayer::traces)]) add("load traces", options.trace_color);
  return key;
}

json legend_json(const ColorScale& scale) {
  std::vector<double> samples;
  for (int k = 0; k < kLegendStops; ++k) samples.push_back(static_cast<double>(k) / (kLegendStops - 1));
  json stops = json::array();
  for (const Rgb& c : map_colors(samples, 0.0, 1.0, scale.map)) stops.push_back({c.r, c.g, c.b});
  return {{"label", scale.label.empty() ? "value" : scale.label},
          {"lo", readout(scale.lo)},
          {"hi", readout(scale.hi)},
          {"stops", std::move(stops)}};
}

std::string file_name(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// JSON text safe inside a <script> element: "<" only occurs in strings,
// where \u003c means the same.
std::string script_json(const json& value) {
  const std::string text = value.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string safe;
  safe.reserve(text.size());
  for (char c : text) {
    if (c == '<') {
      safe += "\\u003c";
    } else {
      safe += c;
    }
  }
  return safe;
}

std::string html_text(const std::string& text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// The template with each placeholder replaced, found in the template itself
// (never in a value put in before it).
std::string fill(std::string_view page, std::vector<std::pair<std::string, std::string>> fields) {
  std::vector<std::pair<std::size_t, const std::pair<std::string, std::string>*>> places;
  for (const auto& field : fields) {
    const auto at = page.find(field.first);
    if (at == std::string_view::npos) throw IoError("the viewer's page template has no " + field.first);
    places.emplace_back(at, &field);
  }
  std::sort(places.begin(), places.end());
  std::string text;
  std::size_t done = 0;
  for (const auto& [at, field] : places) {
    text.append(page.substr(done, at - done));
    text += field->second;
    done = at + field->first.size();
  }
  text.append(page.substr(done));
  return text;
}

// The page's scene (everything but an animation), where each block's
// outline lies in scene["outline"] (vertices [first, second)), and the
// objects that move with each block (its own, then the limit markers it
// carries; indices into scene["objects"]).
struct PageScene {
  json data;
  std::vector<std::pair<std::size_t, std::size_t>> block_outline;
  std::vector<std::vector<int>> carried;
};

PageScene page_scene(const Structure& structure, const std::string& path, const ExportOptions& options) {
  // The outlines are lines in the page; the edge tubes are for mesh files.
  ExportOptions drawn = options;
  drawn.edges = false;
  const std::vector<SceneObject> objects = structure_scene(structure, drawn);

  PageScene page;
  page.block_outline.resize(structure.size());
  page.carried.resize(structure.size());
  json& scene = page.data;
  scene["title"] = options.title.empty() ? file_name(path) : options.title;
  scene["summary"] = summary(structure, options);
  scene["legend"] = options.color_scale ? legend_json(*options.color_scale) : json(nullptr);
  const Rounding rounded(structure.bounds().diagonal());
  json outline = json::array();
  double opacity = 1.0;
  bool present[kSceneLayerNames.entries.size()] = {};
  json items = json::array();
  for (const SceneObject& object : objects) {
    present[static_cast<int>(object.layer)] = true;
    if ((object.layer == SceneLayer::blocks || object.layer == SceneLayer::limit) && object.block >= 0) {
      page.carried[object.block].push_back(static_cast<int>(items.size()));
    }
    if (object.layer == SceneLayer::blocks) {
      opacity = object.opacity;
      page.block_outline[object.block] = {outline.size() / 3, outline.size() / 3 + 2 * object.outline.size()};
    }
    for (const auto& edge : object.outline) {
      for (const Vec3& p : edge) {
        for (int axis = 0; axis < 3; ++axis) outline.push_back(rounded(p[axis]));
      }
    }
    items.push_back(object_json(structure, object, options, rounded));
  }
  if (!outline.empty()) present[static_cast<int>(SceneLayer::edges)] = true;
  json layers = json::array();
  for (const auto& [layer, name] : kSceneLayerNames.entries) {
    if (!present[static_cast<int>(layer)]) continue;
    layers.push_back({{"name", name}, {"visible", layer != SceneLayer::edges || options.edges}});
  }
  scene["layers"] = std::move(layers);
  scene["key"] = key_json(options, objects, present);
  // Arrow length per newton (m/N), for the page's scale bar.
  scene["force_scale"] = present[static_cast<int>(SceneLayer::forces)] ? json(force_arrow_scale(structure, options))
                                                                        : json(nullptr);
  // A planar structure (x-z plane) opens in the front view, orthographic.
  scene["planar"] = structure.planar();
  scene["opacity"] = opacity;
  scene["edge_color"] = {options.edge_color.r, options.edge_color.g, options.edge_color.b};
  scene["outline"] = std::move(outline);
  scene["objects"] = std::move(items);
  scene["animation"] = nullptr;
  return page;
}

void write_page(const std::string& path, const json& scene) {
  const json modules = {{"three.core", web_asset(WebAsset::three_core)},
                        {"three.module", web_asset(WebAsset::three_module)},
                        {"OrbitControls", web_asset(WebAsset::orbit_controls)},
                        {"viewer", web_asset(WebAsset::viewer_script)}};
  write_file_atomically(path, fill(web_asset(WebAsset::viewer_page),
                                   {{"@TITLE@", html_text(scene["title"].get<std::string>())},
                                    {"@VERSION@", version()},
                                    {"@SCENE@", script_json(scene)},
                                    {"@MODULES@", script_json(modules)}}));
}

std::string simulation_summary(const Structure& structure, const SimulationResult& result) {
  std::string text = std::to_string(structure.size()) + " blocks, simulated for " + readout(result.time) + " s";
  if (result.status != SimulationStatus::completed) return text + " (interrupted)";
  text += result.moved ? ": moved, largest displacement " + readout(result.max_displacement) + " m" : ": stayed";
  return text + (result.settled ? ", settled" : ", still moving at the end");
}

// A moving block's track: its objects, centroid, outline and poses per key
// frame, single precision.
json track_json(const Structure& structure, const PageScene& page, int block, const std::vector<RigidPose>& poses) {
  json positions = json::array(), rotations = json::array();
  for (const RigidPose& pose : poses) {
    for (int axis = 0; axis < 3; ++axis) positions.push_back(static_cast<float>(pose.position[axis]));
    for (double c : {pose.rotation.x(), pose.rotation.y(), pose.rotation.z(), pose.rotation.w()}) {
      rotations.push_back(static_cast<float>(c));
    }
  }
  const Vec3& centroid = structure.block(block).centroid();
  return {{"objects", page.carried[block]},
          {"centroid", {centroid.x(), centroid.y(), centroid.z()}},
          {"outline", {page.block_outline[block].first, page.block_outline[block].second}},
          {"positions", std::move(positions)},
          {"rotations", std::move(rotations)}};
}

// The mechanism a page plays, if any: options.mechanism or the result's.
const std::vector<BlockMotion>* page_mechanism(const ExportOptions& options) {
  if (!options.animate_mechanism) return nullptr;
  if (options.mechanism) return options.mechanism;
  return options.result && !options.result->mechanism.empty() ? &options.result->mechanism : nullptr;
}

}  // namespace

void write_viewer_page(const Structure& structure, const std::string& path, const ExportOptions& options) {
  const std::vector<BlockMotion>* mechanism = page_mechanism(options);
  if (!mechanism) {
    write_page(path, page_scene(structure, path, options).data);
    return;
  }
  if (!(options.mechanism_scale >= 0.0) || !std::isfinite(options.mechanism_scale)) {
    throw InvalidArgument("export: mechanism must be a finite distance >= 0 (m), got " +
                          std::to_string(options.mechanism_scale));
  }
  // Drawn where they stand (the scene checks the mechanism against the
  // structure); the player moves them.
  ExportOptions at_rest = options;
  at_rest.mechanism_scale = 0.0;
  PageScene page = page_scene(structure, path, at_rest);
  const double scale = options.mechanism_scale > 0.0 ? options.mechanism_scale
                                                     : kAutomaticMechanismOfSize * structure.bounds().diagonal();
  // Rest, the mechanism at `scale`, rest again: the loop runs smoothly. A
  // rigid motion's slerp and lerp between rest and the extreme are the
  // mechanism at every fraction of it.
  json tracks = json::array();
  for (int i = 0; i < structure.size(); ++i) {
    if (structure.is_support(i)) continue;
    const BlockMotion& motion = (*mechanism)[i];
    const Vec3& centroid = structure.block(i).centroid();
    RigidPose rest{centroid, Quat::Identity()}, moved = rest;
    moved.position += scale * motion.velocity;
    const double angle = scale * motion.rotation.norm();
    if (angle > 0.0) moved.rotation = Quat(Eigen::AngleAxisd(angle, motion.rotation.normalized()));
    tracks.push_back(track_json(structure, page, i, {rest, moved, rest}));
  }
  page.data["summary"] = page.data["summary"].get<std::string>() + "; the collapse mechanism plays, the fastest " +
                         "block's centroid moved " + readout(scale) + " m at its extreme";
  page.data["animation"] = {{"times", {0.0, 1.0, 2.0}},
                            {"tracks", std::move(tracks)},
                            {"autoplay", options.autoplay},
                            {"start", 1.0},
                            {"mechanism", scale}};
  write_page(path, page.data);
}

void write_viewer_page(const Structure& structure, const SimulationResult& result, double fps,
                       const std::string& path, const ExportOptions& options) {
  check_animation(structure, result, fps);
  if (options.result || options.forces || options.thrust || options.interfaces || !options.traces.empty() ||
      options.mechanism_scale > 0.0) {
    throw InvalidArgument("export: an animated page draws the blocks and their edges; interfaces, forces, the "
                          "thrust line, load traces and mechanisms belong to a still (one frame's structure)");
  }
  PageScene page = page_scene(structure, path, options);
  page.data["summary"] = simulation_summary(structure, result);
  const AnimationFrames frames = animation_frames(result, fps);
  json tracks = json::array();
  for (int i = 0; i < structure.size(); ++i) {
    if (structure.is_support(i)) continue;
    std::vector<RigidPose> poses;
    for (const std::vector<RigidPose>& frame : frames.poses) poses.push_back(frame[i]);
    tracks.push_back(track_json(structure, page, i, poses));
  }
  page.data["animation"] = {{"times", frames.times}, {"tracks", std::move(tracks)}, {"autoplay", options.autoplay}};
  write_page(path, page.data);
}

}  // namespace ashlar
