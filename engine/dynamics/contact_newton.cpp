#include "dynamics/contact_newton.hpp"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

namespace ashlar {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat36 = Eigen::Matrix<double, 3, 6>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// The proximal term's weight, relative to the row's Delassus diagonal, is
// kProximal times a damping that starts at min(1, |F|_max /
// kProximalSpeed): a Levenberg-Marquardt weight of the order of |F|
// (Yamashita and Fukushima 2001: the iteration then converges fast to a
// solution even when the solutions are not isolated, as the redundant
// points make them). Measured on the 22-voussoir arch's collapse: a fixed
// 1e-6 left the iterates cycling with steps of 1e-6 and less (the Newton
// direction is right, its slope -2 |F|^2, but valid over a tiny step: the
// Jacobian is near singular); a fixed 1e-3 or 1e-1 converged linearly and
// slowly.
constexpr double kProximal = 1e-2;
constexpr double kProximalSpeed = 1e-2;  // m/s
// The damping's factors after a full step and after a cut one, and its
// most (then the step is a short one down |F|^2's gradient).
constexpr double kLessDamping = 0.1;
constexpr double kMoreDamping = 10.0;
constexpr double kMostDamping = 1e4;
// The iteration stops when |F|_max has not fallen below kStallRatio of
// what it was kStallIterations iterations before (10 iterations cost a
// third more on arches for as many steps solved).
constexpr size_t kStallIterations = 5;
constexpr double kStallRatio = 0.99;
// A step with more rows is solved on a part of them (see
// solve_contact_newton): Newton's iterations on the whole of the 399-block
// vault's 4,700 rows (16,000 unknowns) took 3-5 s a call and left the
// largest |F| above what the sweeps had reached.
constexpr size_t kMostRows = 1000;
// The most rows of that part. On the vault's dynamics (compare_methods_vault_spec's,
// 50 steps; 400-3,500 of its 4,700 rows above the tolerance at a Newton
// call), parts of at most 100 / 200 / 300 / 600 / 1,000 rows left 1 / 1 /
// 1 / 2 / 2 steps unconverged (4 without Newton) in 3.7 / 3.0 / 3.3 / 4.1
// / 9.6 s of CPU (5.8 s without): a larger part costs more per
// iteration than it saves in sweeps.
constexpr size_t kMostPartRows = 200;
// The line search halves the step at most this many times, and accepts a
// step that lowers |F|^2 by at least kArmijo of its rate.
constexpr int kHalvings = 10;
constexpr double kArmijo = 1e-4;

// A row's Jacobian on one of its bodies: the change of the row's relative
// velocity (its frame) per change of the body's (velocity, angular
// velocity), for body b (sign +1) or a (-1).
Mat36 jacobian(const ContactRow& row, const Vec3& arm, double sign) {
  Mat36 g;
  g.leftCols<3>() = sign * row.frame;
  g.rightCols<3>() = -sign * row.frame * cross_matrix(arm);
  return g;
}

Vec6 velocity_of(const BodyVelocities& bodies, int i) {
  Vec6 v;
  v << bodies.linear[i], bodies.angular[i];
  return v;
}

// Per row: its Jacobians, step sizes and proximal weights; per free body:
// its inverse mass matrix.
struct Problem {
  std::vector<int> slot;  // body -> free-body number, -1 fixed
  int free_bodies = 0;
  std::vector<Mat36> ga, gb;
  std::vector<Mat6> inverse_mass;  // per body (zero for a fixed one)
  std::vector<double> rho_n, rho_t;
  std::vector<Vec3> proximal;

  Problem(const std::vector<ContactRow>& rows, const BodyVelocities& bodies) {
    const size_t n = bodies.inverse_mass.size();
    slot.assign(n, -1);
    inverse_mass.assign(n, Mat6::Zero());
    for (size_t i = 0; i < n; ++i) {
      if (bodies.inverse_mass[i] > 0.0) slot[i] = free_bodies++;
      inverse_mass[i].topLeftCorner<3, 3>() = bodies.inverse_mass[i] * Mat3::Identity();
      inverse_mass[i].bottomRightCorner<3, 3>() = bodies.inverse_inertia[i];
    }
    const size_t m = rows.size();
    ga.resize(m);
    gb.resize(m);
    rho_n.resize(m);
    rho_t.resize(m);
    proximal.resize(m);
    for (size_t k = 0; k < m; ++k) {
      const ContactRow& row = rows[k];
      ga[k] = jacobian(row, row.arm_a, -1.0);
      gb[k] = jacobian(row, row.arm_b, 1.0);
      const RowConstants constants = row_constants(row, bodies);
      rho_n[k] = constants.normal_step;
      rho_t[k] = constants.tangent_step;
      proximal[k] = kProximal * constants.diagonal;
    }
  }
};

// One row's Alart-Curnier function (m/s) at impulse p and relative
// velocity u (minus its target), and its generalised Jacobian: the row's
// linearised equation a dP + b du = -F.
struct RowLinearisation {
  Vec3 f = Vec3::Zero();
  Mat3 a = Mat3::Zero(), b = Mat3::Zero();
};

RowLinearisation linearise(const Vec3& p, const Vec3& u, double friction, double rho_n, double rho_t,
                           bool with_jacobian) {
  RowLinearisation l;
  const double pressure = p.x() - rho_n * u.x();
  if (!(pressure > 0.0)) {  // open: F = W_diag-scaled impulse
    l.f.x() = p.x() / rho_n;
    l.f.tail<2>() = p.tail<2>() / rho_t;
    if (with_jacobian) l.a.diagonal() << 1.0 / rho_n, 1.0 / rho_t, 1.0 / rho_t;
    return l;
  }
  l.f.x() = u.x();
  if (with_jacobian) l.b(0, 0) = 1.0;
  const Eigen::Vector2d x = p.tail<2>() - rho_t * u.tail<2>();
  const double radius = friction > 0.0 ? friction * pressure : 0.0;  // inf friction: always within
  const double length = x.norm();
  if (length <= radius) {  // sticking
    l.f.tail<2>() = u.tail<2>();
    if (with_jacobian) l.b.bottomRightCorner<2, 2>().setIdentity();
    return l;
  }
  // Sliding: F_t = (P_t - r e) / rho_t, e = x / |x|, r = mu (P_n - rho_n u_n).
  const Eigen::Vector2d e = x / length;
  l.f.tail<2>() = (p.tail<2>() - radius * e) / rho_t;
  if (with_jacobian) {
    const double s = radius / length;
    const Eigen::Matrix2d q = Eigen::Matrix2d::Identity() - e * e.transpose();
    l.a.bottomRightCorner<2, 2>() = (Eigen::Matrix2d::Identity() - s * q) / rho_t;
    l.a.bottomLeftCorner<2, 1>() = -friction * e / rho_t;
    l.b.bottomLeftCorner<2, 1>() = friction * rho_n * e / rho_t;
    l.b.bottomRightCorner<2, 2>() = s * q;
  }
  return l;
}

ContactNewtonReport solve_whole(std::vector<ContactRow>& rows, BodyVelocities& bodies, double tolerance,
                                int max_iterations) {
  ContactNewtonReport report;
  const size_t m = rows.size();
  if (m == 0 || m > kMostRows) return report;
  const Problem problem(rows, bodies);

  // State: the impulses and the bodies' velocities (6 per body).
  std::vector<Vec3> impulse(m);
  for (size_t k = 0; k < m; ++k) impulse[k] = rows[k].impulse;
  std::vector<Vec6> velocity(bodies.inverse_mass.size());
  for (size_t i = 0; i < velocity.size(); ++i) velocity[i] = velocity_of(bodies, static_cast<int>(i));

  const auto relative = [&](size_t k, const std::vector<Vec6>& v) {
    const ContactRow& row = rows[k];
    Vec3 u = problem.ga[k] * v[row.a] + problem.gb[k] * v[row.b];
    u.x() -= row.target_normal;
    return u;
  };
  const auto function = [&](size_t k, const std::vector<Vec3>& p, const std::vector<Vec6>& v) {
    return linearise(p[k], relative(k, v), rows[k].friction, problem.rho_n[k], problem.rho_t[k], false).f;
  };

  // |F|^2, and the largest |F_k|.
  const auto merit = [&](const std::vector<Vec3>& p, const std::vector<Vec6>& v, double& largest) {
    double sum = 0.0;
    largest = 0.0;
    for (size_t k = 0; k < m; ++k) {
      const Vec3 f = function(k, p, v);
      sum += f.squaredNorm();
      largest = std::max(largest, f.norm());
    }
    return sum;
  };

  double largest = 0.0;
  double phi = merit(impulse, velocity, largest);
  const double initial = largest;
  // Unknowns: dv of the free bodies the rows touch (6 each), then the
  // rows' dP (3 each).
  std::vector<int> unknown(bodies.inverse_mass.size(), -1);
  int nv = 0;
  for (const ContactRow& row : rows) {
    for (const int body : {row.a, row.b}) {
      if (problem.slot[body] >= 0 && unknown[body] < 0) unknown[body] = 6 * nv++;
    }
  }
  nv *= 6;
  const int unknowns = nv + 3 * static_cast<int>(m);
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::SparseMatrix<double> matrix(unknowns, unknowns);
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::VectorXd rhs(unknowns);
  std::vector<Vec3> trial_impulse(m);
  std::vector<Vec6> trial_velocity(velocity.size()), change(velocity.size());
  std::vector<double> history{largest};
  double damping = std::min(1.0, largest / kProximalSpeed);
  while (largest > tolerance && report.iterations < max_iterations) {
    ++report.iterations;
    entries.clear();
    rhs.setZero();
    for (int i = 0; i < nv; ++i) entries.emplace_back(i, i, 1.0);
    for (size_t k = 0; k < m; ++k) {
      const ContactRow& row = rows[k];
      const RowLinearisation l =
          linearise(impulse[k], relative(k, velocity), row.friction, problem.rho_n[k], problem.rho_t[k], true);
      const int r0 = nv + 3 * static_cast<int>(k);
      rhs.segment<3>(r0) = -l.f;
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
          const double value = l.a(r, c) + (r == c ? damping * problem.proximal[k][r] : 0.0);
          if (value != 0.0) entries.emplace_back(r0 + r, r0 + c, value);
        }
      }
      for (const auto& [body, g] : {std::pair<int, const Mat36&>{row.a, problem.ga[k]}, {row.b, problem.gb[k]}}) {
        const int j = unknown[body];
        if (j < 0) continue;
        // Row equations: b G dv; bodies' equations: dv - M^-1 G^T dP = 0.
        const Mat36 bg = l.b * g;
        const Eigen::Matrix<double, 6, 3> mg = problem.inverse_mass[body] * g.transpose();
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 6; ++c) {
            if (bg(r, c) != 0.0) entries.emplace_back(r0 + r, j + c, bg(r, c));
            if (mg(c, r) != 0.0) entries.emplace_back(j + c, r0 + r, -mg(c, r));
          }
        }
      }
    }
    matrix.setFromTriplets(entries.begin(), entries.end());
    lu.analyzePattern(matrix);
    lu.factorize(matrix);
    if (lu.info() != Eigen::Success) break;
    const Eigen::VectorXd step = lu.solve(rhs);
    if (lu.info() != Eigen::Success || !step.allFinite()) break;
    // The bodies' change from the impulses' (exactly, so that the
    // velocities stay those the impulses give).
    std::fill(change.begin(), change.end(), Vec6::Zero());
    for (size_t k = 0; k < m; ++k) {
      const Vec3 dp = step.segment<3>(nv + 3 * static_cast<int>(k));
      change[rows[k].a] += problem.inverse_mass[rows[k].a] * problem.ga[k].transpose() * dp;
      change[rows[k].b] += problem.inverse_mass[rows[k].b] * problem.gb[k].transpose() * dp;
    }
    // Backtracking on |F|^2 (its rate along a Newton step is -2 |F|^2).
    double alpha = 1.0, best_phi = phi, best_alpha = 0.0, best_largest = largest;
    for (int halving = 0; halving <= kHalvings; ++halving, alpha *= 0.5) {
      for (size_t k = 0; k < m; ++k) trial_impulse[k] = impulse[k] + alpha * step.segment<3>(nv + 3 * static_cast<int>(k));
      for (size_t i = 0; i < velocity.size(); ++i) trial_velocity[i] = velocity[i] + alpha * change[i];
      double trial_largest = 0.0;
      const double trial_phi = merit(trial_impulse, trial_velocity, trial_largest);
      if (trial_phi < best_phi) {
        best_phi = trial_phi;
        best_alpha = alpha;
        best_largest = trial_largest;
      }
      if (trial_phi <= (1.0 - 2.0 * kArmijo * alpha) * phi) break;
    }
    // Levenberg-Marquardt's adaptation: a step the line search cut holds
    // a direction the linearisation fits only nearby (a near-singular
    // Jacobian: redundant points, or a point at a kink of F), so the
    // next is damped more; a full step, less.
    damping = best_alpha == 1.0 ? std::max(damping * kLessDamping, std::min(1.0, largest / kProximalSpeed))
                                : std::min(damping * kMoreDamping, kMostDamping);
    if (best_alpha > 0.0) {  // else no step lowered |F|: the next is damped more
      for (size_t k = 0; k < m; ++k) impulse[k] += best_alpha * step.segment<3>(nv + 3 * static_cast<int>(k));
      for (size_t i = 0; i < velocity.size(); ++i) velocity[i] += best_alpha * change[i];
      phi = best_phi;
      largest = best_largest;
    }
    // Stalled (an iterate cycling at a kink of F: a point at its
    // friction limit with next to no slip): the sweeps go on from here.
    history.push_back(largest);
    if (history.size() > kStallIterations && largest > kStallRatio * history[history.size() - 1 - kStallIterations]) break;
  }
  if (largest >= initial) {  // no better than the start: the start is kept
    report.largest = initial;
    return report;
  }
  for (size_t k = 0; k < m; ++k) rows[k].impulse = impulse[k];
  for (size_t i = 0; i < velocity.size(); ++i) {
    bodies.linear[i] = velocity[i].head<3>();
    bodies.angular[i] = velocity[i].tail<3>();
  }
  report.largest = largest;
  return report;
}

}  // namespace

ContactNewtonReport solve_contact_newton(std::vector<ContactRow>& rows, BodyVelocities& bodies, double tolerance,
                                         int max_iterations) {
  if (rows.size() <= kMostRows) return solve_whole(rows, bodies, tolerance, max_iterations);
  // A larger step: Newton on the rows that break the laws by more than
  // the tolerance and every row at their free bodies, the other rows'
  // impulses held (their share of the velocities stays in them), the
  // rows taken from the worst down until kMostPartRows.
  const size_t m = rows.size();
  std::vector<std::pair<double, int>> breaking;
  for (size_t k = 0; k < m; ++k) {
    const ContactRow& row = rows[k];
    const RowConstants constants = row_constants(row, bodies);
    Vec3 u = relative_velocity(row, bodies);
    u.x() -= row.target_normal;
    const double f =
        linearise(row.impulse, u, row.friction, constants.normal_step, constants.tangent_step, false).f.norm();
    if (f > tolerance) breaking.emplace_back(f, static_cast<int>(k));
  }
  if (breaking.empty()) return {};
  std::sort(breaking.begin(), breaking.end(), std::greater<>());
  // Each free body's rows (bodies by index, rows ascending).
  const size_t n = bodies.inverse_mass.size();
  std::vector<int> first(n + 1, 0);
  for (const ContactRow& row : rows) {
    ++first[row.a + 1];
    if (row.b != row.a) ++first[row.b + 1];
  }
  for (size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  std::vector<int> at(first[n]), next(first.begin(), first.end() - 1);
  for (size_t k = 0; k < m; ++k) {
    at[next[rows[k].a]++] = static_cast<int>(k);
    if (rows[k].b != rows[k].a) at[next[rows[k].b]++] = static_cast<int>(k);
  }
  // taken: 1 once chosen, 2 while in `add`.
  std::vector<char> taken(m, 0), body_taken(n, 0);
  std::vector<int> chosen, add;
  for (const auto& [f, k] : breaking) {
    // The row and its free bodies' rows, all or none.
    add.clear();
    const auto consider = [&](int r) {
      if (taken[r] == 0) {
        taken[r] = 2;
        add.push_back(r);
      }
    };
    consider(k);
    for (const int body : {rows[k].a, rows[k].b}) {
      if (!(bodies.inverse_mass[body] > 0.0) || body_taken[body]) continue;
      for (int e = first[body]; e < first[body + 1]; ++e) consider(at[e]);
    }
    const bool fits = chosen.size() + add.size() <= kMostPartRows;
    for (const int r : add) taken[r] = fits ? 1 : 0;
    if (!fits) break;
    for (const int body : {rows[k].a, rows[k].b}) {
      if (bodies.inverse_mass[body] > 0.0) body_taken[body] = 1;
    }
    chosen.insert(chosen.end(), add.begin(), add.end());
  }
  if (chosen.empty()) return {};
  // In the rows' order (the groups' rows stay together).
  std::sort(chosen.begin(), chosen.end());
  std::vector<ContactRow> part;
  part.reserve(chosen.size());
  for (const int k : chosen) part.push_back(rows[k]);
  const ContactNewtonReport report = solve_whole(part, bodies, tolerance, max_iterations);
  for (size_t e = 0; e < chosen.size(); ++e) rows[chosen[e]].impulse = part[e].impulse;
  return report;
}

}  // namespace ashlar
