#include "dynamics/contact_solver.hpp"

#include <algorithm>
#include <cmath>

namespace ashlar {
namespace {

// Per-row constants: the 3x3 Delassus block W = J M^-1 J^T (the velocity
// change of the contact per unit impulse) and the local step sizes.
struct RowConstants {
  double normal_step = 0.0;   // 1 / W_nn
  double tangent_step = 0.0;  // 1 / the largest eigenvalue of W_tt
  double speed_scale = 0.0;   // W_nn: velocity per unit impulse, for the stopping test
};

Mat3 cross_matrix(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

Mat3 delassus(const ContactRow& row, const BodyVelocities& bodies) {
  Mat3 w = Mat3::Zero();
  const auto add = [&](int body, const Vec3& arm) {
    const Mat3 rx = cross_matrix(arm);
    w += bodies.inverse_mass[body] * Mat3::Identity() - rx * bodies.inverse_inertia[body] * rx;
  };
  add(row.a, row.arm_a);
  add(row.b, row.arm_b);
  return row.frame * w * row.frame.transpose();
}

Vec3 relative_velocity(const ContactRow& row, const BodyVelocities& bodies) {
  const Vec3 vb = bodies.linear[row.b] + bodies.angular[row.b].cross(row.arm_b);
  const Vec3 va = bodies.linear[row.a] + bodies.angular[row.a].cross(row.arm_a);
  return row.frame * (vb - va);
}

void apply(const ContactRow& row, const Vec3& local_impulse, BodyVelocities& bodies) {
  const Vec3 p = row.frame.transpose() * local_impulse;
  bodies.linear[row.b] += bodies.inverse_mass[row.b] * p;
  bodies.angular[row.b] += bodies.inverse_inertia[row.b] * row.arm_b.cross(p);
  bodies.linear[row.a] -= bodies.inverse_mass[row.a] * p;
  bodies.angular[row.a] -= bodies.inverse_inertia[row.a] * row.arm_a.cross(p);
}

// The radius of the friction disc, mu P_n (0 when P_n is, whatever mu).
double friction_limit(double friction, double normal) {
  return normal > 0.0 ? friction * normal : 0.0;
}

}  // namespace

Mat3 contact_frame(const Vec3& n) {
  const Vec3 helper = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t1 = n.cross(helper).normalized();
  const Vec3 t2 = n.cross(t1);
  Mat3 frame;
  frame.row(0) = n;
  frame.row(1) = t1;
  frame.row(2) = t2;
  return frame;
}

ContactSolverReport solve_contacts(std::vector<ContactRow>& rows, BodyVelocities& bodies,
                                   const ContactSolverSettings& settings) {
  std::vector<RowConstants> constants(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const Mat3 w = delassus(rows[k], bodies);
    const Eigen::Matrix2d wt = w.bottomRightCorner<2, 2>();
    const double largest = 0.5 * (wt.trace() + std::hypot(wt(0, 0) - wt(1, 1), 2.0 * wt(0, 1)));
    constants[k] = {1.0 / w(0, 0), 1.0 / largest, w(0, 0)};
    // The warm start, clipped to the cone (the friction may have changed).
    Vec3& p = rows[k].impulse;
    p.x() = std::max(0.0, p.x());
    const double limit = friction_limit(rows[k].friction, p.x());
    const double tangential = p.tail<2>().norm();
    if (tangential > limit) p.tail<2>() *= limit / tangential;
    apply(rows[k], p, bodies);
  }
  ContactSolverReport report;
  while (report.sweeps < settings.max_sweeps) {
    ++report.sweeps;
    double largest_change = 0.0;
    for (size_t k = 0; k < rows.size(); ++k) {
      ContactRow& row = rows[k];
      const RowConstants& c = constants[k];
      const Vec3 u = relative_velocity(row, bodies);
      Vec3 p = row.impulse;
      p.x() = std::max(0.0, p.x() - (u.x() - row.target_normal) * c.normal_step);
      Eigen::Vector2d t = p.tail<2>() - c.tangent_step * u.tail<2>();
      const double limit = friction_limit(row.friction, p.x());
      const double tangential = t.norm();
      if (tangential > limit) t *= limit / tangential;
      p.tail<2>() = t;
      const Vec3 change = p - row.impulse;
      if (change.isZero(0.0)) continue;
      apply(row, change, bodies);
      row.impulse = p;
      largest_change = std::max(largest_change, change.norm() * c.speed_scale);
    }
    if (largest_change <= settings.velocity_tolerance) {
      report.converged = true;
      break;
    }
  }
  return report;
}

}  // namespace ashlar
