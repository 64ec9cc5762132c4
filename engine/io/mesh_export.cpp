// Structure export through assimp's exporters (glTF 2.0, OBJ, PLY, STL).
//
// Each block becomes a node named after it with its own flat-shaded mesh:
// every face gets its own copies of its vertices carrying the face normal,
// and polygon faces (convex or not) are ear-clipped in their plane. Each
// block has its own material with its colour. Contact interfaces, when
// asked for, are nodes "interface a-b" (1-based block numbers) holding the
// outer boundary of the contact polygon twice, facing both ways, so that it
// shows from either side in any viewer; holes in a contact polygon are not
// drawn (the outer boundary is filled). Force arrows and the thrust line,
// from an analysis result, are closed solids from force_glyphs.hpp, each a
// node with its own material; blocks turn translucent by default when they
// are drawn, since they run inside the blocks.
//
// Formats, axes (glTF is +Y up) and all-or-nothing writing: assimp_scene.hpp.
// Assimp stores single-precision floats, so mesh files carry about 7
// significant digits; the JSON structure format is the exact one.
#include <cmath>
#include <map>
#include <string>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "io/assimp_scene.hpp"
#include "io/force_glyphs.hpp"
#include "io/mesh_io.hpp"
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
}

// Block i as the mechanism moves it, its fastest centroid `scale` metres.
Block moved_by_mechanism(const Block& block, const BlockMotion& motion, double scale) {
  const double angle = scale * motion.rotation.norm();
  const Block turned = angle > 0.0 ? block.rotated(motion.rotation, angle, block.centroid()) : block;
  return turned.translated(scale * motion.velocity);
}

void add_objects(const Structure& structure, const ExportOptions& options, SceneWriter& writer) {
  const bool glyphs_inside =
      (options.result && (options.forces || options.thrust)) || !options.traces.empty();
  const double opacity = options.block_opacity.value_or(glyphs_inside ? 0.35 : 1.0);
  for (int i = 0; i < structure.size(); ++i) {
    const Rgb color = options.block_colors.empty() ? Rgb{} : options.block_colors[i];
    const bool moves = options.mechanism_scale > 0.0 && !structure.is_support(i);
    const Block& block = structure.block(i);
    writer.add_object(structure.name(i),
                      block_mesh(moves ? moved_by_mechanism(block, options.result->mechanism[i], options.mechanism_scale)
                                       : block),
                      color, false, opacity);
  }
  if (options.interfaces) {
    std::map<std::string, int> uses;
    for (const Interface& contact : structure.interfaces(options.contact)) {
      if (contact.vertices.size() < 3) continue;
      std::string name =
          "interface " + std::to_string(contact.a + 1) + "-" + std::to_string(contact.b + 1);
      const int use = ++uses[name];
      if (use > 1) name += " #" + std::to_string(use);
      FlatMesh mesh;
      mesh.add_polygon(contact.vertices, contact.normal, false);
      mesh.add_polygon(contact.vertices, contact.normal, true);
      writer.add_object(name, mesh, options.interface_color, true);
    }
  }
  for (const NamedGlyph& glyph : equilibrium_glyphs(structure, options)) {
    FlatMesh mesh;
    for (const std::vector<Vec3>& face : glyph.faces) {
      mesh.add_polygon(face, newell_normal(face).normalized(), false);
    }
    writer.add_object(glyph.name, mesh, glyph.color, false);
  }
}

}  // namespace

void export_structure(const Structure& structure, const std::string& path,
                      const ExportOptions& options) {
  SceneWriter writer(path, "export");
  check_options(structure, options);
  add_objects(structure, options, writer);
  writer.write("ashlar structure");
}

}  // namespace ashlar
