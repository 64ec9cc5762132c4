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

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <string>

#include "analysis/equilibrium.hpp"
#include "analysis/mechanism.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "geometry/polygon.hpp"
#include "io/color_map.hpp"
#include "io/force_glyphs.hpp"
#include "io/option_checks.hpp"

namespace ashlar {
namespace {

// The markers of the limit interfaces (ExportOptions::limit): a rod along
// a hinge's axis, the relative rotation of its blocks (the joint's first
// tangent without a mechanism), spanning the joint's vertices along it; a
// disc on a sliding or separating joint.
std::vector<NamedGlyph> limit_glyphs(const Structure& structure, const ExportOptions& options,
                                     const std::vector<BlockMotion>* motion) {
  const std::shared_ptr<const std::vector<Interface>> contacts = structure.interfaces(options.contact);
  const double size = mean_free_block_size(structure);
  std::vector<NamedGlyph> glyphs;
  for (const LimitInterface& entry : *options.limit) {
    const Interface& contact = (*contacts)[entry.interface];
    // With the blocks moved, the marker moves with the joint's free block (a, unless a is a support).
    const int carrier = structure.is_support(contact.a) ? contact.b : contact.a;
    const bool carried = options.mechanism_scale > 0.0 && motion && !structure.is_support(carrier);
    const int mover = structure.is_support(carrier) ? -1 : carrier;
    const auto place = [&](GlyphFaces faces) {
      if (!carried) return faces;
      for (std::vector<Vec3>& face : faces) {
        for (Vec3& p : face) {
          p = moved_point(p, structure.block(carrier).centroid(), (*motion)[carrier], options.mechanism_scale);
        }
      }
      return faces;
    };
    const std::string pair = std::to_string(contact.a + 1) + "-" + std::to_string(contact.b + 1);
    const bool hinge = entry.mode == LimitMode::hinge || entry.mode == LimitMode::hinge_sliding;
    const bool moves = entry.mode != LimitMode::hinge;
    if (hinge) {
      Vec3 axis = contact.u;
      if (motion) {
        const Vec3 relative = (*motion)[contact.b].rotation - (*motion)[contact.a].rotation;
        if (relative.norm() > 0.0) axis = relative.normalized();
      }
      double lo = 0.0, hi = 0.0;
      for (const Vec3& p : contact.vertices) {
        lo = std::min(lo, (p - entry.pivot).dot(axis));
        hi = std::max(hi, (p - entry.pivot).dot(axis));
      }
      // A corner hinge (a point): a rod as long as it is thick, and a little.
      const double half = 0.04 * size;
      if (hi - lo < 2.0 * half) lo = -half, hi = half;
      glyphs.push_back({"hinge " + pair, place(tube_faces({entry.pivot + lo * axis, entry.pivot + hi * axis}, 0.04 * size, 8)),
                        options.hinge_color, SceneLayer::limit, entry.interface, std::nullopt, mover});
    }
    if (moves) {
      const double half = 0.01 * size;
      glyphs.push_back({(entry.mode == LimitMode::separation ? "separation " : "sliding ") + pair,
                        place(tube_faces({contact.center - half * contact.normal, contact.center + half * contact.normal},
                                         0.15 * size, 12)),
                        options.sliding_color, SceneLayer::limit, entry.interface, std::nullopt, mover});
    }
  }
  return glyphs;
}

// The motions the blocks are drawn moved by: the options' own, or the result's.
const std::vector<BlockMotion>* scene_mechanism(const ExportOptions& options) {
  if (options.mechanism) return options.mechanism;
  return options.result && !options.result->mechanism.empty() ? &options.result->mechanism : nullptr;
}

void check_options(const Structure& structure, const ExportOptions& options) {
  check_block_colors(structure, options.block_colors, "export");
  check_color(options.interface_color, "interface_color", "export");
  check_color(options.compression_color, "compression_color", "export");
  check_color(options.tension_color, "tension_color", "export");
  check_color(options.thrust_color, "thrust_color", "export");
  check_color(options.friction_color, "friction_color", "export");
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
  if (options.mechanism && options.mechanism->size() != static_cast<std::size_t>(structure.size())) {
    throw InvalidArgument("export: the mechanism has " + std::to_string(options.mechanism->size()) +
                          " blocks, the structure " + std::to_string(structure.size()));
  }
  if (options.limit) {
    const std::size_t count = structure.interfaces(options.contact)->size();
    for (const LimitInterface& entry : *options.limit) {
      if (entry.interface < 0 || static_cast<std::size_t>(entry.interface) >= count) {
        throw InvalidArgument("export: a limit interface " + std::to_string(entry.interface + 1) +
                              " is not one of the structure's " + std::to_string(count) + " interfaces");
      }
    }
  }
  if (options.mechanism_scale > 0.0 && !scene_mechanism(options)) {
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

}  // namespace

std::vector<SceneObject> structure_scene(const Structure& structure, const ExportOptions& options) {
  check_options(structure, options);
  std::vector<SceneObject> objects;
  const bool glyphs_inside =
      (options.result && (options.forces || options.thrust)) || !options.traces.empty();
  const double opacity = options.block_opacity.value_or(glyphs_inside ? 0.35 : 1.0);
  for (int i = 0; i < structure.size(); ++i) {
    const bool moves = options.mechanism_scale > 0.0 && !structure.is_support(i);
    const Block drawn = moves ? moved_by_mechanism(structure.block(i), (*scene_mechanism(options))[i],
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
  std::vector<NamedGlyph> glyphs = equilibrium_glyphs(structure, options);
  if (options.limit) {
    std::vector<NamedGlyph> markers = limit_glyphs(structure, options, scene_mechanism(options));
    glyphs.insert(glyphs.end(), std::make_move_iterator(markers.begin()), std::make_move_iterator(markers.end()));
  }
  for (NamedGlyph& glyph : glyphs) {
    SceneObject object;
    object.layer = glyph.layer;
    object.name = std::move(glyph.name);
    for (const std::vector<Vec3>& face : glyph.faces) {
      object.mesh.add_polygon(face, newell_normal(face).normalized(), false);
    }
    object.color = glyph.color;
    object.interface = glyph.interface;
    object.block = glyph.block;
    object.arrow = glyph.arrow;
    object.tubes = std::move(glyph.tubes);
    objects.push_back(std::move(object));
  }
  return objects;
}

}  // namespace ashlar
