// A rigid masonry block: a closed, consistently oriented polyhedron whose
// faces are polygons (convex or not) with outward normals, planar to
// rounding or, with a planarity allowance, warped (as fabricated and
// scanned blocks are): the solid is then the one bounded by each face's fan
// of triangles about its centre (the mean of its corners), one surface
// whichever corner a loop starts at, so the two sides of a warped joint
// with the same corners are the same surface; contact uses each face's
// best-fit plane.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "geometry/block_validation.hpp"

namespace ashlar {

// Plane of one face: points x with normal.dot(x) == offset; normal is the
// unit outward normal.
struct FacePlane {
  Vec3 normal;
  double offset = 0.0;
};

// Exact mass properties of the polyhedron (divergence theorem over the faces).
// A face whose corners lie off its best-fit plane by more than this
// fraction of its block's size (bounding-box diagonal) is warped: the
// block's surface there is the fan about the face's centre, which is not
// the convex hull of the corners.
constexpr double kWarpedFace = 1e-9;

struct MassProperties {
  double volume = 0.0;       // m^3, positive for outward-oriented faces
  Vec3 centroid = Vec3::Zero();  // m
};

class Block {
public:
  // vertices: positions in metres. faces: loops of 0-based indices into
  // vertices, counter-clockwise seen from outside. density in kg/m^3.
  // planarity: how far a face's vertices may lie off its best-fit plane, as
  // a fraction of the face's size (its bounding-box diagonal); 0 allows
  // rounding only (1e-6 of the block's size). Throws GeometryError (naming
  // the defect and the block, its vertices and faces as `numbering` names
  // them) unless the input is a valid block; see validate_block() for the
  // checks.
  Block(std::vector<Vec3> vertices, std::vector<FaceLoop> faces,
        double density = kDefaultDensity, std::string name = {}, double planarity = 0.0,
        const MeshNumbering& numbering = {});

  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<FaceLoop>& faces() const { return faces_; }
  const std::vector<FacePlane>& face_planes() const { return planes_; }
  double density() const { return density_; }
  const std::string& name() const { return name_; }
  double planarity() const { return planarity_; }
  // The largest distance (m) of a vertex from its face's best-fit plane.
  double warp() const { return warp_; }
  // Whether some face is warped (kWarpedFace).
  bool warped() const { return warp_ > kWarpedFace * bounds_.diagonal(); }

  double volume() const { return mass_.volume; }
  double mass() const { return density_ * mass_.volume; }  // kg
  const Vec3& centroid() const { return mass_.centroid; }
  const Box3& bounds() const { return bounds_; }
  // True when every vertex lies behind or on every face plane.
  bool convex() const { return convex_; }

  // Rigid motions return new blocks; name and density carry over.
  Block translated(const Vec3& offset) const;
  // Right-handed rotation by angle (radians) about axis through origin.
  Block rotated(const Vec3& axis, double angle, const Vec3& origin) const;
  Block with_name(std::string name) const;
  Block with_density(double density) const;

private:
  struct Trusted {};
  // For rigid motions of an already validated block: no re-validation.
  Block(Trusted, std::vector<Vec3> vertices, std::vector<FaceLoop> faces,
        double density, std::string name, double planarity);
  void compute_derived();

  std::vector<Vec3> vertices_;
  std::vector<FaceLoop> faces_;
  std::vector<FacePlane> planes_;
  double density_;
  std::string name_;
  double planarity_ = 0.0;
  double warp_ = 0.0;
  MassProperties mass_;
  Box3 bounds_;
  bool convex_ = false;
};

using BlockPtr = std::shared_ptr<const Block>;

// A block's size (m): twice the root mean square distance of its vertices
// from their mean, which is a box's diagonal but, unlike the bounding box,
// smooth in the vertices (the gradient needs that) and the same however the
// block is turned.
double block_size(const Block& block);

// "block 'name'", or "unnamed block": how messages name a block outside a
// structure (inside one, Structure::label gives its index too).
std::string block_label(const std::string& name);

// Exact volume and centroid of a closed polyhedron with planar (or not)
// polygon faces; a face of more than three corners is the fan of triangles
// about its centre (face_centre), which is exact for planar faces whatever
// their convexity because the signed contributions cancel, and for warped
// faces the canonical surface of Block.
MassProperties mass_properties(const std::vector<Vec3>& vertices,
                               const std::vector<FaceLoop>& faces);

// How the volume and centroid of mass_properties change with each vertex,
// for the same faces (the structural gradient moves vertices, never the
// topology). Sizes: one entry per vertex.
struct MassPropertiesGradient {
  std::vector<Vec3> volume;    // m^2: d(volume) / d(vertex k)
  std::vector<Mat3> centroid;  // dimensionless: (i, j) = d(centroid_i) / d(vertex k)_j
};

// The centre of a face: the mean of its corners, the apex of its fan.
Vec3 face_centre(const std::vector<Vec3>& vertices, const FaceLoop& face);

// Calls visit(p0, p1, p2) (m) for each triangle of a face's surface,
// oriented as the face: a triangle is itself, a face of more corners the fan
// about its centre.
template <class Visit>
void for_each_surface_triangle(const std::vector<Vec3>& vertices, const FaceLoop& face, Visit visit) {
  if (face.size() == 3) {
    visit(vertices[face[0]], vertices[face[1]], vertices[face[2]]);
    return;
  }
  const Vec3 centre = face_centre(vertices, face);
  for (size_t i = 0; i < face.size(); ++i) {
    visit(centre, vertices[face[i]], vertices[face[(i + 1) % face.size()]]);
  }
}

// Exact derivatives of mass_properties (the same fan triangulation, so they
// also hold for moves that bend a face out of its plane). Throws
// InvalidArgument for a polyhedron of zero volume, whose centroid is undefined.
MassPropertiesGradient mass_properties_gradient(const std::vector<Vec3>& vertices,
                                                const std::vector<FaceLoop>& faces);

// Unit outward normal (Newell) and mean offset of every face.
std::vector<FacePlane> face_planes(const std::vector<Vec3>& vertices,
                                   const std::vector<FaceLoop>& faces);

// The largest distance (m) of a vertex from its own face's plane (planes
// from face_planes): 0 to rounding for planar faces.
double largest_warp(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                    const std::vector<FacePlane>& planes);

// True when no vertex lies more than `slack` (m) in front of any face plane.
bool is_convex_polyhedron(const std::vector<Vec3>& vertices,
                          const std::vector<FacePlane>& planes, double slack);

}  // namespace ashlar
