// Elevation drawings with cairo, written whole or not at all
// (io/cairo_canvas). Blocks are drawn face by face: every face turned
// towards the viewer is projected and painted, farthest first (painter's algorithm on the face centroids), which
// is exact for the extruded planar models and a fair picture of 3D ones.
// Sizes that depend on the image (margins, fonts, line widths) grow with its
// smaller side so that a larger image looks the same, only sharper.
#include "io/drawing.hpp"
#include "io/force_glyphs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>

#include "analysis/equilibrium.hpp"
#include "analysis/mechanism.hpp"
#include "core/error.hpp"
#include "io/cairo_canvas.hpp"
#include "io/option_checks.hpp"

namespace ashlar {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr int kMinImageSize = 100;
// A face turns towards the viewer when its outward normal has at least this
// component against the view direction; faces seen edge-on are skipped.
constexpr double kFacingViewer = 1e-6;
// Arrow sizes, as in the mesh export: the largest arrow is this fraction of
// the mean free-block size. Forces smaller than this fraction of the largest
// (solver round-off, blocks that merely touch) get no arrow (the thrust
// line leaves them out likewise: thrust_polylines).
constexpr double kLargestArrowOfBlockSize = 0.25;
constexpr double kNegligibleForce = 1e-3;

const Rgb kFreeBlockFill{0.87, 0.86, 0.83};
const Rgb kSupportFill{0.70, 0.69, 0.66};
const Rgb kCableColor{0.2, 0.2, 0.22};
const Rgb kCompressionColor{0.15, 0.35, 0.9};
const Rgb kTensionColor{0.9, 0.1, 0.1};

// ---------------------------------------------------------------------------
// Files

// The formats a drawing can be written in: .svg or .png.
ImageFormat drawing_format(const std::string& path, const std::string& what) {
  return image_format(path, {ImageFormat::svg, ImageFormat::png}, what);
}


// ---------------------------------------------------------------------------
// Painting helpers

// Sizes that follow the image's smaller side (px).
struct Metrics {
  double line;    // unit of line widths: 1 px for a smaller side of 800 px
  double font;    // size of body text, 16 px at 800 px
  double margin;  // around the drawing, 32 px at 800 px

  Metrics(int width, int height) {
    const double side = std::min(width, height);
    line = std::max(0.5, side / 800.0);
    font = std::clamp(side / 50.0, 9.0, 48.0);
    margin = std::max(12.0, 0.04 * side);
  }
};

Rgb darker(const Rgb& color, double factor) {
  return {color.r * factor, color.g * factor, color.b * factor};
}

void move_or_line(cairo_t* cr, const Vec2& p, bool first) {
  if (first) {
    cairo_move_to(cr, p.x(), p.y());
  } else {
    cairo_line_to(cr, p.x(), p.y());
  }
}

// Diagonal lines over the current path's area, on a grid anchored at the
// image origin so that neighbouring faces' hatching lines up. Consumes the
// path.
void hatch_path(cairo_t* cr, const Rgb& color, double spacing, double width) {
  double x0, y0, x1, y1;
  cairo_path_extents(cr, &x0, &y0, &x1, &y1);
  cairo_save(cr);
  cairo_clip_preserve(cr);
  cairo_new_path(cr);
  // Lines x - y = c for every multiple c of the spacing that meets the box.
  for (double c = std::floor((x0 - y1) / spacing) * spacing; c <= x1 - y0; c += spacing) {
    cairo_move_to(cr, c + y0, y0);
    cairo_line_to(cr, c + y1, y1);
  }
  set_color(cr, color);
  cairo_set_line_width(cr, width);
  cairo_stroke(cr);
  cairo_restore(cr);
}

// ---------------------------------------------------------------------------
// Elevation

void check_options(const Structure& structure, const ElevationOptions& options) {
  check_image_size(options.width, options.height, kMinImageSize, "draw");
  check_block_colors(structure, options.block_colors, "draw");
  check_color(options.thrust_color, "thrust_color", "draw");
  if (!(options.force_scale >= 0.0) || !std::isfinite(options.force_scale)) {
    throw InvalidArgument("draw: force_scale must be a finite number >= 0 (0: automatic)");
  }
  check_result_of_structure(structure, options.result, options.forces, options.thrust,
                            options.contact, "draw");
  check_color(options.mechanism_color, "mechanism_color", "draw");
  if (!(options.mechanism_scale >= 0.0) || !std::isfinite(options.mechanism_scale)) {
    throw InvalidArgument("draw: mechanism must be a finite distance >= 0 (m), got " +
                          std::to_string(options.mechanism_scale));
  }
  if (options.mechanism_scale > 0.0 && !options.mechanism) {
    throw InvalidArgument("draw: mechanism needs a result with a mechanism (a load factor's, or an unstable analysis's)");
  }
  if (options.mechanism && options.mechanism->size() != static_cast<size_t>(structure.size())) {
    throw InvalidArgument("draw: the mechanism has " + std::to_string(options.mechanism->size()) +
                          " blocks, the structure " + std::to_string(structure.size()));
  }
  if (options.limit) {
    const size_t count = structure.interfaces(options.contact)->size();
    for (const LimitInterface& entry : *options.limit) {
      if (entry.interface < 0 || static_cast<size_t>(entry.interface) >= count) {
        throw InvalidArgument("draw: a limit interface " + std::to_string(entry.interface + 1) +
                              " is not one of the structure's " + std::to_string(count) + " interfaces");
      }
    }
  }
}

struct ProjectedFace {
  std::vector<Vec2> outline;  // px
  double depth = 0.0;         // m, of the face centroid
  int block = -1;
};

// The free blocks moved by the options' mechanism, the supports where
// they stand.
std::vector<Block> moved_blocks(const Structure& structure, const ElevationOptions& options) {
  std::vector<Block> blocks;
  for (int i = 0; i < structure.size(); ++i) {
    blocks.push_back(structure.is_support(i)
                         ? structure.block(i)
                         : moved_by_mechanism(structure.block(i), (*options.mechanism)[i], options.mechanism_scale));
  }
  return blocks;
}

// Every face of every block (block_of(i), i < count) that turns towards the
// viewer, farthest first; faces at equal depth stay in block order.
std::vector<ProjectedFace> visible_faces(int count, const std::function<const Block&(int)>& block_of,
                                         const ElevationProjection& projection) {
  std::vector<ProjectedFace> faces;
  for (int i = 0; i < count; ++i) {
    const Block& block = block_of(i);
    for (size_t f = 0; f < block.faces().size(); ++f) {
      if (block.face_planes()[f].normal.dot(projection.view()) > -kFacingViewer) continue;
      ProjectedFace face;
      face.block = i;
      Vec3 centroid = Vec3::Zero();
      for (const int v : block.faces()[f]) {
        face.outline.push_back(projection(block.vertices()[v]));
        centroid += block.vertices()[v];
      }
      face.depth = projection.depth(centroid / static_cast<double>(block.faces()[f].size()));
      faces.push_back(std::move(face));
    }
  }
  std::stable_sort(faces.begin(), faces.end(), [](const ProjectedFace& a, const ProjectedFace& b) {
    return a.depth > b.depth;
  });
  return faces;
}

void paint_blocks(cairo_t* cr, const Structure& structure, const ElevationProjection& projection,
                  const ElevationOptions& options, const Metrics& metrics) {
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const auto standing = [&](int i) -> const Block& { return structure.block(i); };
  for (const ProjectedFace& face : visible_faces(structure.size(), standing, projection)) {
    const bool support = structure.is_support(face.block);
    const Rgb fill = options.block_colors.empty() ? (support ? kSupportFill : kFreeBlockFill)
                                                  : options.block_colors[face.block];
    const auto trace = [&] {
      cairo_new_path(cr);
      for (size_t k = 0; k < face.outline.size(); ++k) move_or_line(cr, face.outline[k], k == 0);
      cairo_close_path(cr);
    };
    trace();
    set_color(cr, fill);
    cairo_fill_preserve(cr);
    if (support) {
      hatch_path(cr, darker(fill, 0.6), 9.0 * metrics.line, 0.8 * metrics.line);
      trace();  // hatching used the path up
    }
    set_color(cr, darker(fill, 0.4));
    cairo_set_line_width(cr, 0.9 * metrics.line);
    cairo_stroke(cr);
  }
}

void paint_cables(cairo_t* cr, const Structure& structure, const ElevationProjection& projection,
                  const Metrics& metrics) {
  set_color(cr, kCableColor);
  cairo_set_line_width(cr, 1.5 * metrics.line);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const Cable& cable : structure.cables()) {
    move_or_line(cr, projection(cable.from.point), true);
    move_or_line(cr, projection(cable.to.point), false);
    cairo_stroke(cr);
  }
}

// An arrow from tail to tip (px) whose head is a filled triangle.
void paint_arrow(cairo_t* cr, const Vec2& tail, const Vec2& tip, const Metrics& metrics) {
  const double length = (tip - tail).norm();
  // Short arrows keep a shaft, so that their direction still reads.
  const double head = std::min(9.0 * metrics.line, 0.5 * length);
  const Vec2 along = (tip - tail) / length;
  const Vec2 across(-along.y(), along.x());
  const Vec2 base = tip - head * along;
  move_or_line(cr, tail, true);
  move_or_line(cr, base, false);
  cairo_stroke(cr);
  move_or_line(cr, tip, true);
  move_or_line(cr, base + 0.45 * head * across, false);
  move_or_line(cr, base - 0.45 * head * across, false);
  cairo_close_path(cr);
  cairo_fill(cr);
}

void paint_forces(cairo_t* cr, const Structure& structure, const ElevationProjection& projection,
                  const ElevationOptions& options, const Metrics& metrics) {
  const EquilibriumResult& result = *options.result;
  double largest = 0.0;
  for (const InterfaceForces& f : result.interfaces) {
    if (f.resultant.allFinite()) largest = std::max(largest, f.resultant.norm());
  }
  if (largest == 0.0) return;
  const double metres_per_newton =
      options.force_scale > 0.0
          ? options.force_scale
          : kLargestArrowOfBlockSize * mean_free_block_size(structure) / largest;
  const double negligible = kNegligibleForce * largest;
  cairo_set_line_width(cr, 1.5 * metrics.line);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  for (const InterfaceForces& f : result.interfaces) {
    if (!(f.resultant.norm() > negligible) || !f.resultant.allFinite() ||
        !f.center_of_pressure.allFinite()) {
      continue;
    }
    const Vec2 tail = projection(f.center_of_pressure);
    const Vec2 tip = projection(f.center_of_pressure + metres_per_newton * f.resultant);
    // A resultant along the view direction has no arrow to show.
    if ((tip - tail).norm() < metrics.line) continue;
    set_color(cr, f.tension > negligible ? kTensionColor : kCompressionColor);
    paint_arrow(cr, tail, tip, metrics);
  }
}

// The polylines as one stroked path, then a dot at every centre of pressure
// on them.
void paint_thrust(cairo_t* cr, const Structure& structure, const ElevationProjection& projection,
                  const ElevationOptions& options, const Metrics& metrics) {
  set_color(cr, options.thrust_color);
  cairo_set_line_width(cr, 2.0 * metrics.line);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  const std::vector<std::vector<Vec3>> polylines = thrust_polylines(structure, *options.result);
  std::vector<Vec3> points;
  for (const std::vector<Vec3>& polyline : polylines) {
    if (polyline.size() >= 2) {
      for (size_t k = 0; k < polyline.size(); ++k) {
        move_or_line(cr, projection(polyline[k]), k == 0);
      }
    }
    points.insert(points.end(), polyline.begin(), polyline.end());
  }
  cairo_stroke(cr);
  // Polylines share their branch points: one dot each.
  const auto before = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(points.begin(), points.end(), before);
  points.erase(std::unique(points.begin(), points.end()), points.end());
  for (const Vec3& point : points) {
    const Vec2 p = projection(point);
    cairo_new_sub_path(cr);
    cairo_arc(cr, p.x(), p.y(), 3.0 * metrics.line, 0.0, 2.0 * kPi);
  }
  cairo_fill(cr);
}

// The free blocks displaced by the mechanism, outlined with dashes over the
// structure.
void paint_displaced(cairo_t* cr, const Structure& structure, const ElevationProjection& projection,
                     const ElevationOptions& options, const Metrics& metrics) {
  const double dash[] = {5.0 * metrics.line, 3.0 * metrics.line};
  cairo_set_dash(cr, dash, 2, 0.0);
  cairo_set_line_width(cr, 1.2 * metrics.line);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  set_color(cr, options.mechanism_color);
  const std::vector<Block> moved = moved_blocks(structure, options);
  const auto moved_of = [&](int i) -> const Block& { return moved[i]; };
  for (const ProjectedFace& face : visible_faces(structure.size(), moved_of, projection)) {
    if (structure.is_support(face.block)) continue;
    cairo_new_path(cr);
    for (size_t k = 0; k < face.outline.size(); ++k) move_or_line(cr, face.outline[k], k == 0);
    cairo_close_path(cr);
    cairo_stroke(cr);
  }
  cairo_set_dash(cr, nullptr, 0, 0.0);
}

// A marker per limit interface: a filled dot at a hinge's pivot, a hollow
// square at a sliding joint's centre (both for hinge_sliding), a hollow
// circle at a separating joint's centre; black with a white rim, on top.
void paint_limit(cairo_t* cr, const Structure& structure, const ElevationProjection& projection,
                 const ElevationOptions& options, const Metrics& metrics) {
  const std::shared_ptr<const std::vector<Interface>> interfaces = structure.interfaces(options.contact);
  const double size = 5.0 * metrics.line;
  const auto stroke = [&](bool fill) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_set_line_width(cr, 3.0 * metrics.line);
    cairo_stroke_preserve(cr);
    cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
    cairo_set_line_width(cr, 1.5 * metrics.line);
    if (fill) cairo_fill_preserve(cr);
    cairo_stroke(cr);
  };
  for (const LimitInterface& entry : *options.limit) {
    const Vec2 centre = projection((*interfaces)[entry.interface].center);
    const Vec2 pivot = projection(entry.pivot);
    if (entry.mode == LimitMode::sliding || entry.mode == LimitMode::hinge_sliding) {
      cairo_new_path(cr);
      cairo_rectangle(cr, centre.x() - size, centre.y() - size, 2.0 * size, 2.0 * size);
      stroke(false);
    }
    if (entry.mode == LimitMode::hinge || entry.mode == LimitMode::hinge_sliding) {
      cairo_new_path(cr);
      cairo_arc(cr, pivot.x(), pivot.y(), size, 0.0, 2.0 * kPi);
      stroke(true);
    } else if (entry.mode == LimitMode::separation) {
      cairo_new_path(cr);
      cairo_arc(cr, centre.x(), centre.y(), size, 0.0, 2.0 * kPi);
      stroke(false);
    }
  }
}

// A bar of round length under the drawing's left end, half black and half
// white, with its length written after it.
void paint_scale_bar(cairo_t* cr, const ElevationProjection& projection, const ImageRect& fitted,
                     int height, const Metrics& metrics) {
  // A quarter of the drawing's larger side, so that slender drawings get a
  // readable bar too.
  const double length = scale_bar_length(0.25 * std::max(fitted.width, fitted.height) /
                                         projection.scale());
  const double pixels = length * projection.scale();
  const double bar = 0.45 * metrics.font;
  const double middle = height - metrics.margin - 0.5 * metrics.font;
  const double left = fitted.left;
  cairo_set_line_width(cr, metrics.line);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_MITER);
  cairo_rectangle(cr, left, middle - bar / 2, pixels / 2, bar);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  cairo_fill(cr);
  cairo_rectangle(cr, left, middle - bar / 2, pixels, bar);
  cairo_stroke(cr);
  char label[32];
  std::snprintf(label, sizeof label, "%g m", length);
  set_font(cr, metrics.font);
  show_text(cr, label, left + pixels + 0.5 * metrics.font, middle, 0.0);
}

// The title, centred at the top, shrunk to fit the width if need be.
void paint_title(cairo_t* cr, const std::string& title, int width, const Metrics& metrics) {
  const double size = 1.3 * metrics.font;
  set_font(cr, size);
  const double room = width - 2 * metrics.margin;
  const double needed = text_width(cr, title);
  if (needed > room) set_font(cr, size * room / needed);
  cairo_set_source_rgb(cr, 0.0, 0.0, 0.0);
  show_text(cr, title, width / 2.0, metrics.margin + 0.65 * size, 0.5);
}

// Title band height: the title's line and a gap below it.
double title_band(const ElevationOptions& options, const Metrics& metrics) {
  return options.title.empty() ? 0.0 : 2.2 * metrics.font;
}

// Every block vertex and cable end, and the moved blocks' vertices when
// the mechanism is drawn.
std::vector<Vec3> fitted_points(const Structure& structure, const ElevationOptions& options) {
  std::vector<Vec3> points;
  for (int i = 0; i < structure.size(); ++i) {
    const auto& vertices = structure.block(i).vertices();
    points.insert(points.end(), vertices.begin(), vertices.end());
  }
  if (options.mechanism_scale > 0.0) {
    for (const Block& block : moved_blocks(structure, options)) {
      points.insert(points.end(), block.vertices().begin(), block.vertices().end());
    }
  }
  for (const Cable& cable : structure.cables()) {
    points.push_back(cable.from.point);
    points.push_back(cable.to.point);
  }
  return points;
}

// The image rectangle that the projections of points cover.
ImageRect covered_rect(const ElevationProjection& projection, const std::vector<Vec3>& points) {
  Vec2 lo = Vec2::Constant(kInfinity), hi = Vec2::Constant(-kInfinity);
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(projection(p));
    hi = hi.cwiseMax(projection(p));
  }
  return {lo.x(), lo.y(), hi.x() - lo.x(), hi.y() - lo.y()};
}

}  // namespace

// ---------------------------------------------------------------------------
// Public functions

ElevationProjection::ElevationProjection(const Vec3& view_direction,
                                         const std::vector<Vec3>& points, const ImageRect& area) {
  const Vec3 horizontal(view_direction.x(), view_direction.y(), 0.0);
  if (!view_direction.allFinite() || horizontal.norm() == 0.0 ||
      std::abs(view_direction.z()) > 1e-9 * view_direction.norm()) {
    std::ostringstream message;
    message << "view direction must be horizontal (z = 0), non-zero and finite, got ("
            << view_direction.x() << ", " << view_direction.y() << ", " << view_direction.z()
            << ")";
    throw InvalidArgument(message.str());
  }
  if (points.empty()) throw InvalidArgument("elevation projection: no points to fit");
  if (!(area.width > 0.0 && area.height > 0.0)) {
    throw InvalidArgument("elevation projection: the image area has no room");
  }
  view_ = horizontal.normalized();
  right_ = view_.cross(Vec3::UnitZ());
  Vec2 lo = Vec2::Constant(kInfinity), hi = Vec2::Constant(-kInfinity);
  for (const Vec3& p : points) {
    const Vec2 plane(right_.dot(p), p.z());
    lo = lo.cwiseMin(plane);
    hi = hi.cwiseMax(plane);
  }
  const Vec2 extent = hi - lo;
  if (extent.x() > 0.0 && extent.y() > 0.0) {
    scale_ = std::min(area.width / extent.x(), area.height / extent.y());
  } else if (extent.x() > 0.0) {
    scale_ = area.width / extent.x();
  } else if (extent.y() > 0.0) {
    scale_ = area.height / extent.y();
  }
  const Vec2 middle = (lo + hi) / 2;
  offset_ = {area.left + area.width / 2 - scale_ * middle.x(),
             area.top + area.height / 2 + scale_ * middle.y()};
}

Vec2 ElevationProjection::operator()(const Vec3& p) const {
  return {offset_.x() + scale_ * right_.dot(p), offset_.y() - scale_ * p.z()};
}

double scale_bar_length(double at_most) {
  if (!(at_most > 0.0) || !std::isfinite(at_most)) {
    throw InvalidArgument("scale bar: the longest length must be finite and > 0");
  }
  const double power = std::pow(10.0, std::floor(std::log10(at_most)));
  // Round-off in log10 can leave the mantissa a hair outside [1, 10).
  const double mantissa = at_most / power;
  for (const double round : {10.0, 5.0, 2.0}) {
    if (mantissa >= round * (1 - 1e-12)) return round * power;
  }
  return power;
}


ImageRect elevation_area(const ElevationOptions& options) {
  check_image_size(options.width, options.height, kMinImageSize, "draw");
  const Metrics metrics(options.width, options.height);
  // The scale bar's band: its label's height and a gap above it.
  const double scale_band = 2.0 * metrics.font;
  const double top = metrics.margin + title_band(options, metrics);
  return {metrics.margin, top, options.width - 2 * metrics.margin,
          options.height - top - metrics.margin - scale_band};
}

ElevationProjection elevation_projection(const Structure& structure,
                                         const ElevationOptions& options) {
  if (structure.size() == 0) throw InvalidArgument("draw: the structure has no blocks");
  try {
    return ElevationProjection(options.view_direction,
                               fitted_points(structure, options),
                               elevation_area(options));
  } catch (const InvalidArgument& e) {
    throw InvalidArgument(std::string("draw: ") + e.what());
  }
}

void draw_elevation(const Structure& structure, const std::string& path,
                    const ElevationOptions& options) {
  const ImageFormat format = drawing_format(path, "draw");
  check_options(structure, options);
  const ElevationProjection projection = elevation_projection(structure, options);
  const ImageRect fitted = covered_rect(projection, fitted_points(structure, options));
  const Metrics metrics(options.width, options.height);
  render_file(path, format, options.width, options.height, "draw", [&](cairo_t* cr) {
    paint_blocks(cr, structure, projection, options, metrics);
    paint_cables(cr, structure, projection, metrics);
    // Arrows run along the thrust line: on top, so that they show.
    if (options.thrust) paint_thrust(cr, structure, projection, options, metrics);
    if (options.forces) paint_forces(cr, structure, projection, options, metrics);
    if (options.mechanism_scale > 0.0) paint_displaced(cr, structure, projection, options, metrics);
    if (options.limit) paint_limit(cr, structure, projection, options, metrics);
    paint_scale_bar(cr, projection, fitted, options.height, metrics);
    if (!options.title.empty()) paint_title(cr, options.title, options.width, metrics);
  });
}

}  // namespace ashlar
