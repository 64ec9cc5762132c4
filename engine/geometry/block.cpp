#include "geometry/block.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "geometry/block_validation.hpp"
#include "geometry/polygon.hpp"

namespace ashlar {

namespace {

// Vertices this far (relative to the block's size) in front of a face plane
// still count as behind it: rounding of rotated coordinates.
constexpr double kConvexSlack = 1e-9;
// A face warped by more than a fifth of its size is no longer a face.
constexpr double kLargestPlanarity = 0.2;

void check_density(double density, const std::string& name) {
  if (!std::isfinite(density) || density <= 0.0) {
    throw InvalidArgument(block_label(name) + ": density must be a positive finite number (kg/m^3), got " +
                          std::to_string(density));
  }
}

void check_planarity(double planarity, const std::string& name) {
  if (!(planarity >= 0.0 && planarity <= kLargestPlanarity)) {
    std::ostringstream message;
    message << block_label(name) << ": planarity must be a number from 0 to " << kLargestPlanarity
            << " (how far a face may be warped, as a fraction of its size), got " << planarity;
    throw InvalidArgument(message.str());
  }
}

void check_finite(const Vec3& v, const char* what) {
  if (!v.allFinite()) throw InvalidArgument(std::string(what) + " must be finite");
}

}  // namespace

double block_size(const Block& block) {
  const std::vector<Vec3>& vertices = block.vertices();
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : vertices) mean += p;
  mean /= static_cast<double>(vertices.size());
  double sum = 0.0;
  for (const Vec3& p : vertices) sum += (p - mean).squaredNorm();
  return 2.0 * std::sqrt(sum / static_cast<double>(vertices.size()));
}

std::string block_label(const std::string& name) {
  return name.empty() ? std::string("unnamed block") : "block '" + name + "'";
}

Vec3 face_centre(const std::vector<Vec3>& vertices, const FaceLoop& face) {
  Vec3 centre = Vec3::Zero();
  for (int index : face) centre += vertices[index];
  return centre / static_cast<double>(face.size());
}

MassProperties mass_properties(const std::vector<Vec3>& vertices,
                               const std::vector<FaceLoop>& faces) {
  MassProperties props;
  if (vertices.empty()) return props;
  // Tetrahedra from a reference point inside the bounding box keep the
  // products small, so the sums keep their digits far from the origin.
  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  const Vec3 ref = 0.5 * (box.lo + box.hi);
  double six_volume = 0.0;
  Vec3 moment = Vec3::Zero();  // sum of 6V_t * (sum of the three face points)
  for (const FaceLoop& face : faces) {
    for_each_surface_triangle(vertices, face, [&](const Vec3& q0, const Vec3& q1, const Vec3& q2) {
      const Vec3 p0 = q0 - ref, p1 = q1 - ref, p2 = q2 - ref;
      const double d = p0.dot(p1.cross(p2));
      six_volume += d;
      moment += d * (p0 + p1 + p2);
    });
  }
  props.volume = six_volume / 6.0;
  // Centroid of tetrahedron (0, p0, p1, p2) is (p0 + p1 + p2) / 4.
  props.centroid = six_volume != 0.0 ? Vec3(ref + moment / (4.0 * six_volume)) : ref;
  return props;
}

MassPropertiesGradient mass_properties_gradient(const std::vector<Vec3>& vertices,
                                                const std::vector<FaceLoop>& faces) {
  const int n = static_cast<int>(vertices.size());
  MassPropertiesGradient gradient;
  gradient.volume.assign(n, Vec3::Zero());
  gradient.centroid.assign(n, Mat3::Zero());
  if (n == 0) return gradient;
  // The same reference point as mass_properties: the results do not depend
  // on it, the rounding does.
  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  const Vec3 ref = 0.5 * (box.lo + box.hi);
  // With S = 6 V = sum_t d_t, d_t = p0 . (p1 x p2), and M = sum_t d_t (p0 + p1 + p2):
  // dd_t/dp0 = p1 x p2 (and cyclically), dM/dp_a = (p0 + p1 + p2) dd_t/dp_a^T + d_t I.
  double six_volume = 0.0;
  Vec3 moment = Vec3::Zero();
  std::vector<Vec3> d_six_volume(n, Vec3::Zero());
  std::vector<Mat3> d_moment(n, Mat3::Zero());
  // A face of more than three corners is the fan about its centre (the mean
  // of its corners), whose derivatives go to every corner with weight 1/n.
  for (const FaceLoop& face : faces) {
    const size_t n = face.size();
    const bool fan = n > 3;
    const Vec3 centre = fan ? face_centre(vertices, face) : Vec3::Zero();
    Vec3 d_six_volume_centre = Vec3::Zero();
    Mat3 d_moment_centre = Mat3::Zero();
    const size_t triangles = fan ? n : 1;
    for (size_t i = 0; i < triangles; ++i) {
      // corner[a] < 0: the face's centre
      const int corner[3] = {fan ? -1 : face[0], fan ? face[i] : face[1], fan ? face[(i + 1) % n] : face[2]};
      Vec3 p[3];
      for (int a = 0; a < 3; ++a) p[a] = (corner[a] < 0 ? centre : vertices[corner[a]]) - ref;
      const double d = p[0].dot(p[1].cross(p[2]));
      const Vec3 sum = p[0] + p[1] + p[2];
      six_volume += d;
      moment += d * sum;
      for (int a = 0; a < 3; ++a) {
        const Vec3 dd = p[(a + 1) % 3].cross(p[(a + 2) % 3]);
        const Mat3 dm = sum * dd.transpose() + d * Mat3::Identity();
        if (corner[a] < 0) {
          d_six_volume_centre += dd;
          d_moment_centre += dm;
        } else {
          d_six_volume[corner[a]] += dd;
          d_moment[corner[a]] += dm;
        }
      }
    }
    for (int index : face) {
      d_six_volume[index] += d_six_volume_centre / static_cast<double>(n);
      d_moment[index] += d_moment_centre / static_cast<double>(n);
    }
  }
  if (six_volume == 0.0) {
    throw InvalidArgument("mass properties gradient: the polyhedron has zero volume");
  }
  // centroid = ref + M / (4 S)
  for (int k = 0; k < n; ++k) {
    gradient.volume[k] = d_six_volume[k] / 6.0;
    gradient.centroid[k] = d_moment[k] / (4.0 * six_volume) -
                           moment * d_six_volume[k].transpose() / (4.0 * six_volume * six_volume);
  }
  return gradient;
}

Block::Block(std::vector<Vec3> vertices, std::vector<FaceLoop> faces, double density,
             std::string name, double planarity, const MeshNumbering& numbering)
    : vertices_(std::move(vertices)),
      faces_(std::move(faces)),
      density_(density),
      name_(std::move(name)),
      planarity_(planarity) {
  check_density(density_, name_);
  check_planarity(planarity_, name_);
  validate_block(vertices_, faces_, block_label(name_), planarity_, numbering);
  compute_derived();
}

Block::Block(Trusted, std::vector<Vec3> vertices, std::vector<FaceLoop> faces, double density,
             std::string name, double planarity)
    : vertices_(std::move(vertices)),
      faces_(std::move(faces)),
      density_(density),
      name_(std::move(name)),
      planarity_(planarity) {
  compute_derived();
}

std::vector<FacePlane> face_planes(const std::vector<Vec3>& vertices,
                                   const std::vector<FaceLoop>& faces) {
  std::vector<FacePlane> planes;
  planes.reserve(faces.size());
  std::vector<Vec3> loop;
  for (const FaceLoop& face : faces) {
    loop.clear();
    for (int index : face) loop.push_back(vertices[index]);
    FacePlane plane;
    plane.normal = newell_normal(loop).normalized();
    double offset = 0.0;
    for (const Vec3& p : loop) offset += plane.normal.dot(p);
    plane.offset = offset / static_cast<double>(loop.size());
    planes.push_back(plane);
  }
  return planes;
}

double largest_warp(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                    const std::vector<FacePlane>& planes) {
  double warp = 0.0;
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int index : faces[f]) {
      warp = std::max(warp, std::abs(planes[f].normal.dot(vertices[index]) - planes[f].offset));
    }
  }
  return warp;
}

bool is_convex_polyhedron(const std::vector<Vec3>& vertices,
                          const std::vector<FacePlane>& planes, double slack) {
  for (const FacePlane& plane : planes) {
    for (const Vec3& p : vertices) {
      if (plane.normal.dot(p) - plane.offset > slack) return false;
    }
  }
  return true;
}

void Block::compute_derived() {
  bounds_ = Box3{};
  for (const Vec3& p : vertices_) bounds_.add(p);
  planes_ = ashlar::face_planes(vertices_, faces_);
  mass_ = mass_properties(vertices_, faces_);
  warp_ = largest_warp(vertices_, faces_, planes_);
  // A warped face's own vertices lie up to warp_ in front of its best-fit
  // plane, convex block or not.
  convex_ = is_convex_polyhedron(vertices_, planes_, std::max(kConvexSlack * bounds_.diagonal(), warp_));
}

Block Block::translated(const Vec3& offset) const {
  check_finite(offset, "translation");
  std::vector<Vec3> moved = vertices_;
  for (Vec3& p : moved) p += offset;
  return Block(Trusted{}, std::move(moved), faces_, density_, name_, planarity_);
}

Block Block::rotated(const Vec3& axis, double angle, const Vec3& origin) const {
  check_finite(axis, "rotation axis");
  check_finite(origin, "rotation origin");
  if (!std::isfinite(angle)) throw InvalidArgument("rotation angle must be finite");
  if (axis.norm() == 0.0) throw InvalidArgument("rotation axis must not be zero");
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  std::vector<Vec3> moved = vertices_;
  for (Vec3& p : moved) p = origin + rotation * (p - origin);
  return Block(Trusted{}, std::move(moved), faces_, density_, name_, planarity_);
}

Block Block::with_name(std::string name) const {
  return Block(Trusted{}, vertices_, faces_, density_, std::move(name), planarity_);
}

Block Block::with_density(double density) const {
  check_density(density, name_);
  return Block(Trusted{}, vertices_, faces_, density, name_, planarity_);
}

}  // namespace ashlar
