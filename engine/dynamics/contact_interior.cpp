#include "dynamics/contact_interior.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/sparse_cholesky.hpp"
#include "dynamics/body_blocks.hpp"

namespace ashlar {
namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat36 = Eigen::Matrix<double, 3, 6>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// Interior-point iterations per cone program at most (they took 7-15).
constexpr int kIterations = 60;
// A cone program is solved when every row's complementarity x . z is at
// most kGap times the tolerance times the largest impulse, and its
// equations hold to kFeasible times the tolerance as velocities (the
// velocities are then made again from the impulses: what the equations
// miss moves the rows' velocities by about as much). Near the answer the
// bodies' system is ill-conditioned (S grows as 1 / gap): a box sliding
// at 0.3 m/s kept its momentum equation only to 1e-10 m/s there.
constexpr double kGap = 1e-3;
constexpr double kFeasible = 0.1;
// Steps go this fraction of the way to the cones' boundary.
constexpr double kStepBack = 0.99;
// The start's least impulse, as a fraction of the largest (see below).
constexpr double kLift = 1e-3;
// The shift moves this fraction of the way to the slips' mu |u_t| each
// round. The full way alternates between two answers on walls shaken
// past their load factor. The 106-block wall at 1.5 g, 2 Hz for 0.1 s
// (100 steps): 0.35 / 0.5 / 0.65 left every step converged in 18.6 /
// 13.2 / 10.9 s, 0.8 left 23 unconverged (the fixed point out of its 30
// rounds on most calls).
constexpr double kRelaxation = 0.65;
// A round whose shift moved by less than this fraction of the tolerance
// ends the fixed point: the cone programs' accuracy bounds it.
constexpr double kLeastMove = 0.1;

// A row's Jacobian on one of its bodies: the change of the row's relative
// velocity (its frame) per change of the body's (velocity, angular
// velocity), for body b (sign +1) or a (-1).
Mat36 jacobian(const ContactRow& row, const Vec3& arm, double sign) {
  Mat36 g;
  g.leftCols<3>() = sign * row.frame;
  g.rightCols<3>() = -sign * row.frame * cross_matrix(arm);
  return g;
}

// The second-order cone Q = { x_0 >= |(x_1, x_2)| }: its Jordan product,
// its inverse (u with jordan(lambda, u) = b), how far inside it x is.
Vec3 jordan(const Vec3& x, const Vec3& y) {
  Vec3 p;
  p << x.dot(y), x.x() * y.tail<2>() + y.x() * x.tail<2>();
  return p;
}
Vec3 jordan_divide(const Vec3& lambda, const Vec3& b) {
  const double det = lambda.x() * lambda.x() - lambda.tail<2>().squaredNorm();
  Vec3 u;
  u.x() = (lambda.x() * b.x() - lambda.tail<2>().dot(b.tail<2>())) / det;
  u.tail<2>() = (b.tail<2>() - u.x() * lambda.tail<2>()) / lambda.x();
  return u;
}
double cone_margin(const Vec3& x) { return x.x() - x.tail<2>().norm(); }

// D a and D^-1 a for D = diag(mu, 1, 1), the scaling that takes a row's
// friction cone to Q (see solve_contact_interior).
Vec3 scaled(const Vec3& a, double mu) { return Vec3(mu * a.x(), a.y(), a.z()); }
Vec3 unscaled(const Vec3& a, double mu) { return Vec3(a.x() / mu, a.y(), a.z()); }

// The largest a with x + a d in Q (x inside it): the least positive root
// of (x_0 + a d_0)^2 - |x_t + a d_t|^2; infinity if there is none.
double step_to_boundary(const Vec3& x, const Vec3& d) {
  const double a = d.x() * d.x() - d.tail<2>().squaredNorm();
  const double b = x.x() * d.x() - x.tail<2>().dot(d.tail<2>());
  const double c = x.x() * x.x() - x.tail<2>().squaredNorm();
  const double inf = std::numeric_limits<double>::infinity();
  if (a == 0.0) return b < 0.0 ? -c / (2.0 * b) : inf;
  const double disc = b * b - a * c;
  if (disc < 0.0) return inf;
  const double t = -(b + std::copysign(std::sqrt(disc), b));
  double least = inf;
  for (const double root : {t / a, t != 0.0 ? c / t : inf}) {
    if (root > 0.0) least = std::min(least, root);
  }
  return least;
}

// Nesterov-Todd scaling of x (impulses) and z (velocities) inside Q: W,
// symmetric positive definite, with W x = W^-1 z = lambda. With
// xb = x / sqrt(x^T J x), zb likewise (J = diag(1, -1, -1)), and
// w = (zb + J xb) / sqrt(2 (1 + xb . zb)):
// W = beta [[w_0, w_t^T], [w_t, I + w_t w_t^T / (1 + w_0)]], W^-1 the same
// with -w_t over beta, beta = (z^T J z / x^T J x)^(1/4).
struct Scaling {
  Mat3 w, w_inverse;
  Vec3 lambda;
};
Scaling nesterov_todd(const Vec3& x, const Vec3& z) {
  const double xjx = x.x() * x.x() - x.tail<2>().squaredNorm();
  const double zjz = z.x() * z.x() - z.tail<2>().squaredNorm();
  const Vec3 xb = x / std::sqrt(xjx), zb = z / std::sqrt(zjz);
  const Vec3 w = (zb + Vec3(xb.x(), -xb.y(), -xb.z())) / std::sqrt(2.0 * (1.0 + xb.dot(zb)));
  const double beta = std::pow(zjz / xjx, 0.25);
  Mat3 h = Mat3::Identity();
  h(0, 0) = w.x();
  h.bottomRightCorner<2, 2>() += w.tail<2>() * w.tail<2>().transpose() / (1.0 + w.x());
  Scaling s;
  s.w = h;
  s.w.col(0).tail<2>() = w.tail<2>();
  s.w.row(0).tail<2>() = w.tail<2>().transpose();
  s.w_inverse = h;
  s.w_inverse.col(0).tail<2>() = -w.tail<2>();
  s.w_inverse.row(0).tail<2>() = -w.tail<2>().transpose();
  s.w *= beta;
  s.w_inverse /= beta;
  s.lambda = s.w * x;
  return s;
}

}  // namespace

ContactInteriorReport solve_contact_interior(std::vector<ContactRow>& rows, BodyVelocities& bodies,
                                             double tolerance, int max_fixed_point, std::vector<double>& s) {
  ContactInteriorReport report;
  const int m = static_cast<int>(rows.size());
  if (m == 0) return report;
  for (const ContactRow& row : rows) {
    if (!(row.friction > 0.0) || !std::isfinite(row.friction)) return report;
  }
  const int n = static_cast<int>(bodies.inverse_mass.size());
  std::vector<int> slot(n, -1);
  int free_bodies = 0;
  for (int i = 0; i < n; ++i) {
    if (bodies.inverse_mass[i] > 0.0) slot[i] = free_bodies++;
  }
  const int unknowns = 6 * free_bodies;

  // Per row: its Jacobians, the share of u of a fixed body's velocity, and
  // the sweeps' step sizes (for the residual below). Per free body: its
  // mass matrix.
  std::vector<Mat36> ga(m), gb(m);
  std::vector<Vec3> fixed_u(m, Vec3::Zero());
  std::vector<RowConstants> constants(m);
  std::vector<std::pair<int, int>> links;
  for (int k = 0; k < m; ++k) {
    const ContactRow& row = rows[k];
    ga[k] = jacobian(row, row.arm_a, -1.0);
    gb[k] = jacobian(row, row.arm_b, 1.0);
    constants[k] = row_constants(row, bodies);
    for (const auto& [body, g] : {std::pair<int, const Mat36*>{row.a, &ga[k]}, {row.b, &gb[k]}}) {
      if (slot[body] >= 0) continue;
      Vec6 velocity;
      velocity << bodies.linear[body], bodies.angular[body];
      fixed_u[k] += *g * velocity;
    }
    if (slot[row.a] >= 0 && slot[row.b] >= 0) {
      links.emplace_back(std::min(slot[row.a], slot[row.b]), std::max(slot[row.a], slot[row.b]));
    }
  }
  std::sort(links.begin(), links.end());
  links.erase(std::unique(links.begin(), links.end()), links.end());
  BodyBlocks blocks;
  std::vector<int> pattern_rows = blocks.set(free_bodies, links);
  SparseCholeskyOptions whole;
  whole.split_from_rows = std::numeric_limits<int>::max();
  whole.block_rows = 6;  // BodyBlocks' 6 x 6 blocks
  SparseCholesky cholesky(unknowns, blocks.column_starts(), std::move(pattern_rows), whole);
  std::vector<Mat6> mass(free_bodies, Mat6::Zero());
  std::vector<Eigen::LDLT<Mat6>> mass_factor(free_bodies);
  Eigen::VectorXd v(unknowns);
  for (int i = 0; i < n; ++i) {
    if (slot[i] < 0) continue;
    Mat6& mi = mass[slot[i]];
    mi.topLeftCorner<3, 3>() = Mat3::Identity() / bodies.inverse_mass[i];
    mi.bottomRightCorner<3, 3>() = bodies.inverse_inertia[i].inverse();
    mass_factor[slot[i]].compute(mi);
    v.segment<3>(6 * slot[i]) = bodies.linear[i];
    v.segment<3>(6 * slot[i] + 3) = bodies.angular[i];
  }

  // J w for row k; J^T y (y per row, contact frame); M w; M^-1 w.
  const auto row_times = [&](const Eigen::VectorXd& w, int k) {
    Vec3 u = Vec3::Zero();
    if (slot[rows[k].a] >= 0) u += ga[k] * w.segment<6>(6 * slot[rows[k].a]);
    if (slot[rows[k].b] >= 0) u += gb[k] * w.segment<6>(6 * slot[rows[k].b]);
    return u;
  };
  const auto transpose_times = [&](const std::vector<Vec3>& y, Eigen::VectorXd& out) {
    out.setZero(unknowns);
    for (int k = 0; k < m; ++k) {
      if (slot[rows[k].a] >= 0) out.segment<6>(6 * slot[rows[k].a]) += ga[k].transpose() * y[k];
      if (slot[rows[k].b] >= 0) out.segment<6>(6 * slot[rows[k].b]) += gb[k].transpose() * y[k];
    }
  };
  const auto mass_times = [&](const Eigen::VectorXd& w) {
    Eigen::VectorXd out(unknowns);
    for (int j = 0; j < free_bodies; ++j) out.segment<6>(6 * j) = mass[j] * w.segment<6>(6 * j);
    return out;
  };
  const auto mass_solve = [&](const Eigen::VectorXd& w) {
    Eigen::VectorXd out(unknowns);
    for (int j = 0; j < free_bodies; ++j) out.segment<6>(6 * j) = mass_factor[j].solve(w.segment<6>(6 * j));
    return out;
  };

  // The free velocities' momentum q = M v - J^T P (the velocities hold the
  // impulses applied), and the velocities impulses P give: M^-1 (q + J^T P).
  std::vector<Vec3> impulse(m);
  for (int k = 0; k < m; ++k) impulse[k] = rows[k].impulse;
  Eigen::VectorXd g;
  transpose_times(impulse, g);
  const Eigen::VectorXd q = mass_times(v) - g;
  const auto velocities_of = [&](const std::vector<Vec3>& p) {
    Eigen::VectorXd momentum;
    transpose_times(p, momentum);
    return mass_solve(momentum + q);
  };
  // The largest residual (contact_solver.hpp's row_residual) of impulses p
  // at velocities w. An interior point's impulses are never on the cone's
  // boundary: a row whose normal impulse a sweep's pass would set to zero
  // (at most rho_n times its separating velocity) counts as open, and
  // friction a pass would put on its limit (|P_t - rho_t u_t| >= mu P_n)
  // as on it.
  const auto largest_residual = [&](const std::vector<Vec3>& p, const Eigen::VectorXd& w) {
    double largest = 0.0;
    for (int k = 0; k < m; ++k) {
      ContactRow row = rows[k];
      row.impulse = p[k];
      const Vec3 u = row_times(w, k) + fixed_u[k];
      if (row.impulse.x() <= constants[k].normal_step * (u.x() - row.target_normal)) {
        row.impulse.setZero();
      } else {
        const double limit = row.friction * row.impulse.x();
        const double friction = row.impulse.tail<2>().norm();
        if (friction > 0.0 && (row.impulse.tail<2>() - constants[k].tangent_step * u.tail<2>()).norm() >= limit) {
          row.impulse.tail<2>() *= limit / friction;
        }
      }
      largest = std::max(largest, row_residual(row, u));
    }
    return largest;
  };
  const double start_residual = largest_residual(impulse, v);
  report.largest = start_residual;
  if (start_residual <= tolerance) return report;
  double best_residual = start_residual;
  std::vector<Vec3> best_impulse;
  Eigen::VectorXd best_v;

  // Scaled variables: x = D P and z = D^-1 U in Q, D = diag(mu, 1, 1), so
  // that P . U = x . z. The shift s = mu |u_t| starts at zero on a step's
  // first call: the first program is the associated one (slip with
  // dilatancy), whose answer is at rest where statics holds. Started from
  // the sweeps' slips, the fixed point drifted on the 399-block vault's
  // first step (standing) to a sliding answer: 1.2 cm in 0.05 s where the
  // sweeps' answer and this one stand still.
  std::vector<Vec3> x(m), z(m), shift(m), dx(m), dz(m), r(m), r2(m), y(m);
  std::vector<Scaling> scaling(m);
  if (s.size() != static_cast<size_t>(m)) s.assign(m, 0.0);
  std::vector<double> impulse_scale(m);
  for (int k = 0; k < m; ++k) {
    impulse_scale[k] = constants[k].normal_step * (row_times(v, k) + fixed_u[k]).norm() * rows[k].friction;
  }
  Eigen::VectorXd rhs, dv;
  for (int round = 0; round < max_fixed_point; ++round) {
    ++report.fixed_point_iterations;
    // z = D^-1 (J v + e), e the shift, the target and a fixed body's share.
    for (int k = 0; k < m; ++k) {
      const double mu = rows[k].friction;
      shift[k] = fixed_u[k];
      shift[k].x() += s[k] - rows[k].target_normal;
      x[k] = scaled(impulse[k], mu);
      z[k] = unscaled(row_times(v, k) + shift[k], mu);
    }
    // Into the cones' interior: by 1.5 times the farthest outside, then
    // Mehrotra's shift of x by half x . z over the sum of z_0 and of z the
    // other way (with floors: kLift of the largest impulse, or of the
    // impulse that would stop a row's relative velocity, rho_n |u|; a
    // thousandth of the tolerance).
    double x_out = 0.0, z_out = 0.0, x_scale = 0.0;
    for (int k = 0; k < m; ++k) {
      x_out = std::max(x_out, -cone_margin(x[k]));
      z_out = std::max(z_out, -cone_margin(z[k]));
      x_scale = std::max({x_scale, x[k].norm(), impulse_scale[k]});
    }
    double xz = 0.0, x0 = 0.0, z0 = 0.0;
    for (int k = 0; k < m; ++k) {
      x[k].x() += 1.5 * x_out;
      z[k].x() += 1.5 * z_out;
      xz += x[k].dot(z[k]);
      x0 += x[k].x();
      z0 += z[k].x();
    }
    const double x_floor = kLift * x_scale, z_floor = 1e-3 * tolerance;
    const double x_lift = std::max(0.5 * xz / std::max(z0, z_floor * m), x_floor);
    const double z_lift = std::max(0.5 * xz / std::max(x0, x_floor * m), z_floor);
    for (int k = 0; k < m; ++k) {
      x[k].x() += x_lift;
      z[k].x() += z_lift;
    }
    bool solved = false;
    for (int iteration = 0; iteration <= kIterations; ++iteration) {
      // Residuals R1 = M v - J^T D^-1 x - q (as velocities, M^-1 R1) and
      // R2 = z - D^-1 (J v + e); the mean gap x . z.
      for (int k = 0; k < m; ++k) y[k] = unscaled(x[k], rows[k].friction);
      transpose_times(y, g);
      const Eigen::VectorXd r1 = mass_times(v) - g - q;
      double gap = 0.0, largest_xz = 0.0, largest_r2 = 0.0, p_scale = 0.0;
      for (int k = 0; k < m; ++k) {
        r2[k] = z[k] - unscaled(row_times(v, k) + shift[k], rows[k].friction);
        gap += x[k].dot(z[k]);
        largest_xz = std::max(largest_xz, x[k].dot(z[k]));
        largest_r2 = std::max(largest_r2, r2[k].cwiseAbs().maxCoeff());
        p_scale = std::max(p_scale, y[k].norm());
      }
      gap /= m;
      const double largest_r1 = mass_solve(r1).cwiseAbs().maxCoeff();
      if (largest_xz <= kGap * tolerance * p_scale && largest_r1 <= kFeasible * tolerance &&
          largest_r2 <= kFeasible * tolerance) {
        solved = true;
        break;
      }
      if (iteration == kIterations) break;
      ++report.iterations;
      // The bodies' system M + J^T S J, S = D^-1 W^-2 D^-1 per row.
      double* values = cholesky.values();
      std::fill(values, values + cholesky.nonzeros(), 0.0);
      for (int j = 0; j < free_bodies; ++j) blocks.add(values, j, j, mass[j]);
      for (int k = 0; k < m; ++k) {
        scaling[k] = nesterov_todd(x[k], z[k]);
        const Vec3 d_inverse(1.0 / rows[k].friction, 1.0, 1.0);
        const Mat3 s_k =
            d_inverse.asDiagonal() * (scaling[k].w_inverse * scaling[k].w_inverse) * d_inverse.asDiagonal();
        const int a = slot[rows[k].a], b = slot[rows[k].b];
        if (a >= 0) blocks.add(values, a, a, ga[k].transpose() * s_k * ga[k]);
        if (b >= 0) blocks.add(values, b, b, gb[k].transpose() * s_k * gb[k]);
        if (a >= 0 && b >= 0) {
          if (a < b) blocks.add(values, a, b, ga[k].transpose() * s_k * gb[k]);
          else blocks.add(values, b, a, gb[k].transpose() * s_k * ga[k]);
        }
      }
      if (!(gap > 0.0) || !std::isfinite(gap) || !cholesky.factorize()) break;
      // The direction for complementarity targets r (W dx + W^-1 dz = r):
      // (M + J^T S J) dv = -R1 + J^T D^-1 (W^-1 r + W^-2 R2), then
      // dz = D^-1 J dv - R2, dx = W^-1 r - W^-2 dz. Returns the largest
      // step that keeps x and z in their cones.
      const auto direction = [&]() {
        for (int k = 0; k < m; ++k) {
          const Mat3& wi = scaling[k].w_inverse;
          const Vec3 t = wi * (r[k] + wi * r2[k]);
          y[k] = unscaled(t, rows[k].friction);
        }
        transpose_times(y, g);
        rhs = g - r1;
        cholesky.solve(rhs, dv);
        double step = std::numeric_limits<double>::infinity();
        for (int k = 0; k < m; ++k) {
          dz[k] = unscaled(row_times(dv, k), rows[k].friction) - r2[k];
          const Mat3& wi = scaling[k].w_inverse;
          dx[k] = wi * (r[k] - wi * dz[k]);
          step = std::min({step, step_to_boundary(x[k], dx[k]), step_to_boundary(z[k], dz[k])});
        }
        return step;
      };
      // Mehrotra: the affine direction (r = -lambda), the centring
      // sigma = (its gap / the gap)^3, then the combined direction with
      // the second-order term.
      for (int k = 0; k < m; ++k) r[k] = -scaling[k].lambda;
      const double affine = std::min(1.0, direction());
      double gap_affine = 0.0;
      for (int k = 0; k < m; ++k) gap_affine += (x[k] + affine * dx[k]).dot(z[k] + affine * dz[k]);
      const double sigma = std::pow(std::max(0.0, gap_affine / m) / gap, 3.0);
      for (int k = 0; k < m; ++k) {
        const Vec3 second = jordan(scaling[k].w_inverse * dz[k], scaling[k].w * dx[k]);
        r[k] = jordan_divide(scaling[k].lambda, Vec3(sigma * gap, 0.0, 0.0) - second) - scaling[k].lambda;
      }
      const double step = std::min(1.0, kStepBack * direction());
      v += step * dv;
      for (int k = 0; k < m; ++k) {
        x[k] += step * dx[k];
        z[k] += step * dz[k];
      }
    }
    if (!solved) break;
    // The program's impulses, the velocities they give, and the shift
    // they call for.
    for (int k = 0; k < m; ++k) impulse[k] = unscaled(x[k], rows[k].friction);
    v = velocities_of(impulse);
    double moved = 0.0;
    for (int k = 0; k < m; ++k) {
      const double next = rows[k].friction * (row_times(v, k) + fixed_u[k]).tail<2>().norm();
      moved = std::max(moved, std::abs(next - s[k]));
      s[k] += kRelaxation * (next - s[k]);
    }
    const double residual = largest_residual(impulse, v);
    if (residual < best_residual) {
      best_residual = residual;
      best_impulse = impulse;
      best_v = v;
    }
    if (residual <= tolerance || moved <= kLeastMove * tolerance) break;
  }
  report.largest = best_residual;
  report.improved = best_residual < start_residual;
  if (report.improved) {
    for (int k = 0; k < m; ++k) rows[k].impulse = best_impulse[k];
    for (int i = 0; i < n; ++i) {
      if (slot[i] < 0) continue;
      bodies.linear[i] = best_v.segment<3>(6 * slot[i]);
      bodies.angular[i] = best_v.segment<3>(6 * slot[i] + 3);
    }
  }
  return report;
}

}  // namespace ashlar
