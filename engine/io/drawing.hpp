// 2D drawings: elevations of a structure with its line of thrust (as in
// Shin 2014, figure 7). Format from the extension: .svg (vector, sizes in
// pt) or .png (raster, sizes in pixels). Colour legends: io/color_legend.
// Image coordinates have x to the right and y down, in px (pt for SVG).
#pragma once

#include <string>
#include <vector>

#include "analysis/mechanism.hpp"
#include "core/types.hpp"
#include "io/image_rect.hpp"
#include "io/mesh_io.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct EquilibriumResult;

// Orthographic projection of 3D points onto a vertical plane, scaled and
// shifted into an image rectangle: the elevation seen by a viewer looking
// horizontally along a view direction.
class ElevationProjection {
public:
  // view_direction: 3 vector, the way the viewer looks; horizontal (z = 0)
  //   and non-zero, any length. Image x runs along view_direction x z (for
  //   +y: along +x; for -x: along +y), image y down along -z.
  // points: n 3D points (m), n >= 1: their projections are fitted into
  //   `area` (px) with equal scale on both axes, centred; a set with no
  //   extent on either image axis is fitted by the other one, a single
  //   point gets 1 px per metre.
  // Throws InvalidArgument for a vertical, zero or non-finite direction, no
  // points or an area without positive width and height.
  ElevationProjection(const Vec3& view_direction, const std::vector<Vec3>& points,
                      const ImageRect& area);

  // Image position (px) of point p (m).
  Vec2 operator()(const Vec3& p) const;
  // Distance (m) of p along the view direction: larger is farther away.
  double depth(const Vec3& p) const { return view_.dot(p); }
  double scale() const { return scale_; }  // px per metre
  const Vec3& view() const { return view_; }    // unit view direction
  const Vec3& right() const { return right_; }  // unit, horizontal, image x

private:
  Vec3 view_, right_;
  double scale_ = 1.0;
  Vec2 offset_ = Vec2::Zero();  // image position of the origin
};

struct ElevationOptions {
  // The way the viewer looks, horizontal: +y (default, "front") shows the
  // x-z plane with x to the right; -x ("side") shows the y-z plane with y to
  // the right.
  Vec3 view_direction{0.0, 1.0, 0.0};
  int width = 1200, height = 800;  // px for .png, pt for .svg; each in [100, 16384]
  std::string title;               // drawn above the structure; none when empty
  // One fill colour per block (size() == structure.size()), or empty for
  // light grey free blocks and darker, hatched supports.
  std::vector<Rgb> block_colors;
  ContactOptions contact;  // must be those of the analysis that gave `result`

  // An analysis of this very structure (same blocks, interfaces found with
  // the same `contact` options), needed by `thrust` and `forces`; not owned,
  // it must outlive the call.
  const EquilibriumResult* result = nullptr;
  // The line of thrust: thrust_polylines(structure, *result), with a dot at
  // each of their points.
  bool thrust = false;
  // An arrow per interface from its centre of pressure along the resultant
  // acting on block b, its length proportional to the resultant's size,
  // projected like the blocks; blue in compression, red with tension.
  // Interfaces whose resultant is below 1e-3 of the largest get none.
  bool forces = false;
  // Arrow length per newton (m/N); 0 makes the largest arrow a quarter of the
  // mean size (bounding-box diagonal) of the free blocks.
  double force_scale = 0.0;
  Rgb thrust_color{0.93, 0.26, 0.05};

  // A collapse mechanism (ashlar.load_factor's, or an unstable analysis's),
  // not owned, outliving the call; none when null. `limit` (interface
  // indices into structure.interfaces(contact)) gets markers: a filled dot
  // at a hinge's pivot, a hollow square at a sliding joint's centre (both
  // for hinge_sliding), a hollow circle at a separating joint's centre.
  const std::vector<LimitInterface>* limit = nullptr;
  // One motion per block; with mechanism_scale > 0 (m) the free blocks are
  // outlined (dashed, mechanism_color) where the mechanism moves them:
  // moved_by_mechanism, the fastest centroid mechanism_scale metres (as the
  // export's ExportOptions::mechanism_scale); 0 draws none.
  const std::vector<BlockMotion>* mechanism = nullptr;
  double mechanism_scale = 0.0;
  Rgb mechanism_color{0.45, 0.1, 0.55};
};



// The rectangle (px) that draw_elevation fits the structure into: inside
// the margins, below the title when there is one, above the scale bar.
// Throws InvalidArgument for sizes outside [100, 16384].
ImageRect elevation_area(const ElevationOptions& options);

// The projection draw_elevation uses: every block vertex and cable end
// fitted into elevation_area(options). Throws InvalidArgument for an empty structure or
// a bad view direction.
ElevationProjection elevation_projection(const Structure& structure,
                                         const ElevationOptions& options);

// Draws the structure's elevation: every block face that faces the viewer,
// farthest first, filled and outlined; cables as lines; the line of thrust
// and force arrows when asked for; a scale bar (a round length: 1, 2 or 5
// times a power of ten metres) and the title. Written atomically.
// Throws InvalidArgument for an unknown extension (not .svg or .png), bad
// options (sizes, colours, view, thrust or forces without a result, a
// result of another structure), IoError when the file cannot be written.
void draw_elevation(const Structure& structure, const std::string& path,
                    const ElevationOptions& options);

// The length of a scale bar (m): the largest 1, 2 or 5 times a power of ten
// that is at most `at_most` (m, finite, > 0); e.g. 3.7 -> 2, 0.9 -> 0.5.
// Throws InvalidArgument otherwise.
double scale_bar_length(double at_most);

}  // namespace ashlar
