// Small value types shared by every engine layer. SI units throughout:
// metres, kilograms, newtons; z is up.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products are defined here
#include <limits>
#include <vector>

namespace ashlar {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec2 = Eigen::Vector2d;

// A polygon loop given by vertex indices into its block's vertex list.
using FaceLoop = std::vector<int>;

// A 2D polygon loop in the plane frame of some face; counter-clockwise for
// outer boundaries, clockwise for holes.
using Loop2 = std::vector<Vec2>;

constexpr double kDefaultDensity = 2400.0;  // kg/m^3, typical stone
constexpr double kGravity = 9.81;           // m/s^2, along -z
constexpr double kPi = 3.14159265358979323846;

// Axis-aligned bounding box; empty() until a point is added.
struct Box3 {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return lo.x() > hi.x(); }
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void add(const Box3& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  double diagonal() const { return empty() ? 0.0 : (hi - lo).norm(); }
};

}  // namespace ashlar
