#include "dynamics/contact_solver.hpp"

#include <algorithm>
#include <cmath>

namespace ashlar {
namespace {

// Most passes over one group's rows per sweep.
constexpr int kGroupPasses = 10;

// Per-row constants: the 3x3 Delassus block W = J M^-1 J^T (the velocity
// change of the contact per unit impulse) and the local step sizes.
struct RowConstants {
  double normal_step = 0.0;   // 1 / W_nn
  double tangent_step = 0.0;  // 1 / the largest eigenvalue of W_tt
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

// How far (m/s) the relative velocity u of a row breaks the contact laws at
// the row's impulse: the normal velocity off its target where the contact
// presses, or below it where it does not; a sticking contact's slip; a
// sliding one's slip off the direction opposite its friction.
double residual(const ContactRow& row, const Vec3& u) {
  const Vec3& p = row.impulse;
  double normal = p.x() > 0.0 ? std::abs(u.x() - row.target_normal) : std::max(0.0, row.target_normal - u.x());
  const Eigen::Vector2d slip = u.tail<2>();
  const double friction = p.tail<2>().norm();
  const double limit = friction_limit(row.friction, p.x());
  double tangential = 0.0;
  if (friction < limit * (1.0 - 1e-12)) {
    tangential = slip.norm();
  } else if (friction > 0.0) {
    tangential = (slip + slip.norm() * p.tail<2>() / friction).norm();
  }
  return std::max(normal, tangential);
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
    constants[k] = {1.0 / w(0, 0), 1.0 / largest};
    // The warm start, clipped to the cone (the friction may have changed).
    Vec3& p = rows[k].impulse;
    p.x() = std::max(0.0, p.x());
    const double limit = friction_limit(rows[k].friction, p.x());
    const double tangential = p.tail<2>().norm();
    if (tangential > limit) p.tail<2>() *= limit / tangential;
    apply(rows[k], p, bodies);
  }
  // Groups: runs of consecutive rows between the same two bodies.
  std::vector<size_t> group_start{0};
  for (size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].a != rows[k - 1].a || rows[k].b != rows[k - 1].b) group_start.push_back(k);
  }
  group_start.push_back(rows.size());
  const size_t groups = group_start.size() - 1;

  // One pass over rows [begin, end): each row's local update; returns the
  // largest residual met.
  const auto pass = [&](size_t begin, size_t end) {
    double largest = 0.0;
    for (size_t k = begin; k < end; ++k) {
      ContactRow& row = rows[k];
      const RowConstants& c = constants[k];
      const Vec3 u = relative_velocity(row, bodies);
      largest = std::max(largest, residual(row, u));
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
    }
    return largest;
  };

  ContactSolverReport report;
  while (report.sweeps < settings.max_sweeps && groups > 0) {
    ++report.sweeps;
    double largest_residual = 0.0;
    // Symmetric Gauss-Seidel over the groups: forward and backward in turn,
    // so that what one end of the order learns reaches the other in one
    // sweep pair. Each group (the points of one contact between two
    // blocks) is solved to the tolerance, or kGroupPasses passes, before
    // the next: a stack's weight then goes down it in one sweep.
    const bool forward = report.sweeps % 2 == 1;
    for (size_t visit = 0; visit < groups; ++visit) {
      const size_t g = forward ? visit : groups - 1 - visit;
      const size_t begin = group_start[g], end = group_start[g + 1];
      double group_residual = pass(begin, end);
      largest_residual = std::max(largest_residual, group_residual);
      for (int inner = 1; inner < kGroupPasses && group_residual > 0.5 * settings.velocity_tolerance; ++inner) {
        group_residual = pass(begin, end);
      }
    }
    if (largest_residual <= settings.velocity_tolerance) {
      report.converged = true;
      break;
    }
  }
  if (groups == 0) report.converged = true;
  return report;
}

}  // namespace ashlar
