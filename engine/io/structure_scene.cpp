// The objects of a structure's export.
//
// Each block is an object named after it with its own flat-shaded mesh:
// every face gets its own copies of its vertices carrying the face normal,
// and polygon faces (convex or not) are ear-clipped in their plane. Contact
// interfaces, when asked for, are objects "interface a-b" (1-based block
// numbers) holding the outer boundary of the contact polygon twice, facing
// both ways, so that it shows from either side in any viewer; holes in a
// contact polygon are not drawn (the outer boundary is filled). Force
// arrows and the thrust line, from an analysis result, are closed solids
// from force_glyphs.hpp; blocks turn translucent by default when they are
// drawn, since they run inside the blocks.
#include "io/structure_scene.hpp"

#include <cmath>
#include <map>
#include <string>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "geometry/polygon.hpp"
#include "io/color_map.hpp"
#include "io/force_glyphs.hpp"
#include "io/option_checks.hpp"

namespace ashlar {
namespace {

void check_options(const Structure& structure, const ExportOptions& options) {
  check_block_colors(structure, options.block_colors, "export");
  check_color(options.interface_color, "interface_color", "export");
  check_color(options.compression_color, "compression_color", "export");
  check_color(options.tension_color, "tension_color", "export");
  check_color(options.thrust_color, "thrust_color", "export");
  if (options.block_opacity && !(*options.block_opacity >= 0.0 && *options.block_opacity <= 1.0)) {
    throw InvalidArgument("export: block_opacity must lie in [0, 1], got " +
                          std::to_string(*options.block_opacity));
  }
  if (!(options.force_scale >= 0.0) || !std::isfinite(options.force_scale)) {
    throw InvalidArgument("export: force_scale must be a finite number >= 0 (0: automatic)");
  }
  if (!(options.negligible_force >= 0.0 && options.negligible_force < 1.0)) {
    throw InvalidArgument("export: negligible_force must lie in [0, 1)");
  }
  check_result_of_structure(structure, options.result, options.forces, options.thrust,
                            options.contact, "export");
  if (!(options.mechanism_scale >= 0.0) || !std::isfinite(options.mechanism_scale)) {
    throw InvalidArgument("export: mechanism must be a finite distance >= 0 (m), got " +
                          std::to_string(options.mechanism_scale));
  }
  if (options.mechanism_scale > 0.0 && (!options.result || options.result->mechanism.empty())) {
    throw InvalidArgument(std::string("export: mechanism needs ") +
                          (options.result ? "an unstable result: this one stands, it has no mechanism"
                                          : "the result of an analysis (result = r) that found the structure unstable"));
  }
  if (const auto& scale = options.color_scale) {
    if (scale->values.size() != static_cast<std::size_t>(structure.size())) {
      throw InvalidArgument("export: color_scale needs one value per block (" + std::to_string(structure.size()) +
                            "), got " + std::to_string(scale->values.size()));
    }
    if (!std::isfinite(scale->lo) || !std::isfinite(scale->hi)) {
      throw InvalidArgument("export: color_scale's range must be finite, got {" +
                            shortest_number(scale->lo) + ", " + shortest_number(scale->hi) + "}");
    }
    check_color_map(scale->map);
  }
}

// Block i as the mechanism moves it, its fastest centroid `scale` metres.
Block moved_by_mechanism(const Block& block, const BlockMotion& motion, double scale) {
  const double angle = scale * motion.rotation.norm();
  const Block turned = angle > 0.0 ? block.rotated(motion.rotation, angle, block.centroid()) : block;
  return turned.translated(scale * motion.velocity);
}

}  // namespace

std::vector<SceneObject> structure_scene(const Structure& structure, const ExportOptions& options) {
  check_options(structure, options);
  std::vector<SceneObject> objects;
  const bool glyphs_inside =
      (options.result && (options.forces || options.thrust)) || !options.traces.empty();
  const double opacity = options.block_opacity.value_or(glyphs_inside ? 0.35 : 1.0);
  for (int i = 0; i < structure.size(); ++i) {
    const bool moves = options.mechanism_scale > 0.0 && !structure.is_support(i);
    const Block drawn = moves ? moved_by_mechanism(structure.block(i), options.result->mechanism[i],
                                                   options.mechanism_scale)
                              : structure.block(i);
    SceneObject object;
    object.layer = SceneLayer::blocks;
    object.name = structure.name(i);
    object.mesh = block_mesh(drawn);
    object.color = options.block_colors.empty() ? Rgb{} : options.block_colors[i];
    object.opacity = opacity;
    object.block = i;
    object.outline = block_edges(drawn);
    objects.push_back(std::move(object));
  }
  if (options.interfaces) {
    std::map<std::string, int> uses;
    const std::shared_ptr<const std::vector<Interface>> contacts_list = structure.interfaces(options.contact);
    const std::vector<Interface>& contacts = *contacts_list;
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const Interface& contact = contacts[k];
      if (contact.vertices.size() < 3) continue;
      std::string name =
          "interface " + std::to_string(contact.a + 1) + "-" + std::to_string(contact.b + 1);
      const int use = ++uses[name];
      if (use > 1) name += " #" + std::to_string(use);
      SceneObject object;
      object.layer = SceneLayer::interfaces;
      object.name = std::move(name);
      object.mesh.add_polygon(contact.vertices, contact.normal, false);
      object.mesh.add_polygon(contact.vertices, contact.normal, true);
      object.color = options.interface_color;
      object.two_sided = true;
      object.interface = static_cast<int>(k);
      objects.push_back(std::move(object));
    }
  }
  for (NamedGlyph& glyph : equilibrium_glyphs(structure, options)) {
    SceneObject object;
    object.layer = glyph.layer;
    object.name = std::move(glyph.name);
    for (const std::vector<Vec3>& face : glyph.faces) {
      object.mesh.add_polygon(face, newell_normal(face).normalized(), false);
    }
    object.color = glyph.color;
    object.interface = glyph.interface;
    object.arrow = glyph.arrow;
    objects.push_back(std::move(object));
  }
  return objects;
}

}  // namespace ashlar
