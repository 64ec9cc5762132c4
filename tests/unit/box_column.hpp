// A column of equal boxes on a fixed ground, as the contact solve sees one
// step of it: the tests of the contact solver and of its Newton method.
#pragma once

#include <vector>

#include "core/types.hpp"
#include "dynamics/contact_solver.hpp"

namespace ashlar::test {

constexpr double kStep = 1e-3;                       // s
constexpr double kSide = 0.5, kHeight = 0.2;         // m
constexpr double kDensity = 2400.0;                  // kg/m^3
constexpr double kMass = kDensity * kSide * kSide * kHeight;

struct Column {
  std::vector<ContactRow> rows;
  BodyVelocities bodies;
};

// Body 0 the ground (fixed), bodies 1..n boxes kSide x kSide x kHeight
// stacked on it, their velocities the step's free ones under gravity and a
// horizontal body force `sideways` (m/s^2, along x); each joint's four
// corners a row, the column's top joint first (the simulation's order).
inline Column column(int n, double sideways, double friction) {
  Column c;
  const double inertia_xy = kMass / 12.0 * (kSide * kSide + kHeight * kHeight);
  const double inertia_z = kMass / 12.0 * 2.0 * kSide * kSide;
  const Mat3 inverse_inertia = Vec3(1.0 / inertia_xy, 1.0 / inertia_xy, 1.0 / inertia_z).asDiagonal();
  c.bodies.linear.assign(n + 1, Vec3::Zero());
  c.bodies.angular.assign(n + 1, Vec3::Zero());
  c.bodies.inverse_mass.assign(n + 1, 1.0 / kMass);
  c.bodies.inverse_inertia.assign(n + 1, inverse_inertia);
  c.bodies.inverse_mass[0] = 0.0;
  c.bodies.inverse_inertia[0] = Mat3::Zero();
  for (int i = 1; i <= n; ++i) c.bodies.linear[i] = kStep * Vec3(sideways, 0, -kGravity);
  const auto centroid = [](int body) { return Vec3(0, 0, body == 0 ? -0.5 * kHeight : (body - 0.5) * kHeight); };
  for (int joint = n - 1; joint >= 0; --joint) {  // between body joint (below) and joint + 1
    for (const double x : {-0.5 * kSide, 0.5 * kSide}) {
      for (const double y : {-0.5 * kSide, 0.5 * kSide}) {
        ContactRow row;
        row.a = joint;
        row.b = joint + 1;
        const Vec3 point(x, y, joint * kHeight);
        row.arm_a = point - centroid(row.a);
        row.arm_b = point - centroid(row.b);
        row.frame = contact_frame(Vec3::UnitZ());
        row.friction = friction;
        c.rows.push_back(row);
      }
    }
  }
  return c;
}

}  // namespace ashlar::test
