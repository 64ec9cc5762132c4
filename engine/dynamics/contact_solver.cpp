#include "dynamics/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/sparse_cholesky.hpp"
#include "dynamics/contact_newton.hpp"

namespace ashlar {
namespace {

// Most passes over one group's rows per sweep.
constexpr int kGroupPasses = 10;
// Sweeps between two global steps of one solve.
constexpr int kSweepsPerGlobalStep = 4;
// Global steps in a row at most, each without the points the one before
// left pulling.
constexpr int kGlobalStepRepeats = 2;
// A solve stops taking global steps once this many left a larger residual
// than the sweep before them.
constexpr int kGlobalStepsWorse = 3;
// The global step's compliance: each constrained component c of row k
// gets E = kCompliance W_cc s_k (m/s per N s), so that a solve leaves
// about kCompliance of the residual it corrects (its error is
// W dP - r = -E dP) while the bodies' system stays well conditioned
// (1e-5 left a 40-block column unsolved, 1e-3 needed more sweeps on
// arches). s_k, from 1 to kMostSpread, is the largest normal impulse at
// the row's blocks over the row's own (kMostSpread for a point not yet
// pressed beside pressed ones): the points of one face, and the head and
// bed joints of a wall, share a load in no particular way, and the least
// change in E's norm then shares a change of load in proportion to what
// each point already carries, instead of evenly, which would pull on
// the lightly pressed ones.
constexpr double kCompliance = 1e-4;
constexpr double kMostSpread = 1e4;
// Solves with one factorisation in a global step: the first and two
// refinements on what is left of r.
constexpr int kRefinements = 3;
// Newton's method (contact_newton.hpp) iterates until every row's
// Alart-Curnier function is below this fraction of the tolerance, or
// kNewtonIterations iterations.
constexpr double kNewtonTolerance = 0.5;
constexpr int kNewtonIterations = 30;
// Sweeps whose residual is still above this many tolerances are not
// stalled but slow (a load still on its way through the structure): they
// go on alone.
constexpr double kNewtonFrom = 100.0;

// Per-row constants: the 3x3 Delassus block W = J M^-1 J^T (the velocity
// change of the contact per unit impulse) and the local step sizes.
struct RowConstants {
  double normal_step = 0.0;   // 1 / W_nn
  double tangent_step = 0.0;  // 1 / the largest eigenvalue of W_tt
  Vec3 diagonal = Vec3::Zero();  // W_nn, W_t1t1, W_t2t2 (m/s per N s)
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

// Which components of a row the global step holds as equalities: none
// (the row is open), the normal (pressed and sliding: friction at its
// limit and slipping by more than `tolerance` (m/s); or frictionless), or
// all three (pressed, or approaching, and sticking). A point at its
// friction limit that does not slip sticks: the points of one face share
// its load in no particular way, and a lightly pressed corner often has
// all the friction it may have while its face does not slide.
int constrained_components(const ContactRow& row, const Vec3& u, double tolerance) {
  const Vec3& p = row.impulse;
  if (!(p.x() > 0.0) && !(u.x() < row.target_normal)) return 0;
  if (!(row.friction > 0.0)) return 1;
  if (!(p.x() > 0.0)) return 3;
  const bool at_limit = p.tail<2>().norm() >= friction_limit(row.friction, p.x()) * (1.0 - 1e-12);
  return at_limit && u.tail<2>().norm() > tolerance ? 1 : 3;
}

}  // namespace

// The global step's factorisation and the active set's pattern it was made
// for. Unknowns: 6 per free body (velocity, then angular velocity), free
// bodies in index order.
struct ContactSolver::Factor {
  std::vector<int> slot;                      // body -> its free-body number, -1 fixed
  std::vector<std::pair<int, int>> links;     // free-body numbers (i < j) linked by a constrained row, sorted
  std::vector<std::vector<int>> column_bodies;  // per free body j: the linked i <= j, ascending (j last)
  std::vector<int> column_starts;             // of the 6 m x 6 m upper triangle
  std::unique_ptr<SparseCholesky> cholesky;
  bool usable = false;

  // Position in the values of entry (6 i + r, 6 j + c), i <= j, r <= c if i == j.
  int position(int i, int r, int j, int c) const {
    const std::vector<int>& bodies = column_bodies[j];
    const int k = static_cast<int>(std::lower_bound(bodies.begin(), bodies.end(), i) - bodies.begin());
    return column_starts[6 * j + c] + 6 * k + r;
  }

  void set_pattern(int free_bodies, std::vector<std::pair<int, int>> linked) {
    links = std::move(linked);
    column_bodies.assign(free_bodies, {});
    for (const auto& [i, j] : links) column_bodies[j].push_back(i);
    std::vector<int> rows;
    column_starts.assign(6 * free_bodies + 1, 0);
    for (int j = 0; j < free_bodies; ++j) {
      std::vector<int>& bodies = column_bodies[j];
      bodies.push_back(j);  // links are sorted: the others come ascending
      for (int c = 0; c < 6; ++c) {
        for (size_t k = 0; k < bodies.size(); ++k) {
          const int last = bodies[k] == j ? c : 5;
          for (int r = 0; r <= last; ++r) rows.push_back(6 * bodies[k] + r);
        }
        column_starts[6 * j + c + 1] = static_cast<int>(rows.size());
      }
    }
    cholesky = std::make_unique<SparseCholesky>(6 * free_bodies, column_starts, std::move(rows));
  }
};

ContactSolver::ContactSolver() : factor_(std::make_unique<Factor>()) {}
ContactSolver::~ContactSolver() = default;

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

ContactSolverReport ContactSolver::solve(std::vector<ContactRow>& rows, BodyVelocities& bodies,
                                         const ContactSolverSettings& settings) {
  std::vector<RowConstants> constants(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    const Mat3 w = delassus(rows[k], bodies);
    const Eigen::Matrix2d wt = w.bottomRightCorner<2, 2>();
    const double largest = 0.5 * (wt.trace() + std::hypot(wt(0, 0) - wt(1, 1), 2.0 * wt(0, 1)));
    constants[k] = {1.0 / w(0, 0), 1.0 / largest, w.diagonal()};
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
  const size_t groups = rows.empty() ? 0 : group_start.size() - 1;
  ContactSolverReport report;

  // One pass over rows [begin, end): each row's local update; returns the
  // largest residual met, and where (worst).
  const auto pass = [&](size_t begin, size_t end, int& worst) {
    double largest = 0.0;
    for (size_t k = begin; k < end; ++k) {
      ContactRow& row = rows[k];
      const RowConstants& c = constants[k];
      const Vec3 u = relative_velocity(row, bodies);
      const double r = residual(row, u);
      if (r > largest) {
        largest = r;
        worst = static_cast<int>(k);
      }
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

  // The global step (see the header): the number of pressed points it
  // left pulling, which the projection releases; -1 when there was nothing
  // to take it on (no point pressed yet), -2 when the factorisation
  // failed.
  Factor& f = *factor_;
  // The bodies' unknowns, and the pattern: every pair of free bodies with
  // a row between them (whether pressed or not, so that it holds while
  // points open and close), set up at the solve's first global step.
  int free_bodies = -1;
  const auto set_up_pattern = [&]() {
    if (f.slot.size() != bodies.inverse_mass.size()) f.usable = false;
    f.slot.resize(bodies.inverse_mass.size());
    free_bodies = 0;
    for (size_t i = 0; i < bodies.inverse_mass.size(); ++i) {
      const int slot = bodies.inverse_mass[i] > 0.0 ? free_bodies++ : -1;
      if (f.slot[i] != slot) f.usable = false;
      f.slot[i] = slot;
    }
    std::vector<std::pair<int, int>> links;
    for (size_t g = 0; g < groups; ++g) {
      const int a = f.slot[rows[group_start[g]].a], b = f.slot[rows[group_start[g]].b];
      if (a >= 0 && b >= 0) links.emplace_back(std::min(a, b), std::max(a, b));
    }
    std::sort(links.begin(), links.end());
    links.erase(std::unique(links.begin(), links.end()), links.end());
    if (!f.usable || links != f.links) {
      f.set_pattern(free_bodies, std::move(links));
      f.usable = true;
    }
  };
  const auto global_step = [&]() {
    if (free_bodies < 0) set_up_pattern();
    std::vector<int> components(rows.size());
    std::vector<Vec3> target(rows.size());
    int constrained = 0;
    for (size_t k = 0; k < rows.size(); ++k) {
      const Vec3 u = relative_velocity(rows[k], bodies);
      components[k] = constrained_components(rows[k], u, settings.velocity_tolerance);
      target[k] = Vec3(rows[k].target_normal, 0.0, 0.0) - u;
      constrained += components[k];
    }
    if (constrained == 0) return -1;
    std::vector<double> most(bodies.inverse_mass.size(), 0.0);
    for (const ContactRow& row : rows) {
      most[row.a] = std::max(most[row.a], row.impulse.x());
      most[row.b] = std::max(most[row.b], row.impulse.x());
    }
    std::vector<Vec3> compliance(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      if (components[k] == 0) continue;
      const double p = rows[k].impulse.x();
      const double reference = std::max(f.slot[rows[k].a] >= 0 ? most[rows[k].a] : 0.0,
                                        f.slot[rows[k].b] >= 0 ? most[rows[k].b] : 0.0);
      const double spread = p > 0.0 ? std::clamp(reference / p, 1.0, kMostSpread) : reference > 0.0 ? kMostSpread : 1.0;
      compliance[k] = kCompliance * spread * constants[k].diagonal;
    }
    // 1 / E per component, 0 for those not held.
    std::vector<Vec3> weight(rows.size(), Vec3::Zero());
    for (size_t k = 0; k < rows.size(); ++k) {
      for (int c = 0; c < components[k]; ++c) weight[k][c] = 1.0 / compliance[k][c];
    }
    // A new factorisation each step: E follows the impulses, and a
    // factorisation made for another E would give dP = E^-1 (r - J dv)
    // from a dv that does not belong to it (a stale one was tried: its
    // error, scaled by 1 / E, blew up shaken walls).
    {
      double* values = f.cholesky->values();
      std::fill(values, values + f.cholesky->nonzeros(), 0.0);
      for (size_t i = 0; i < bodies.inverse_mass.size(); ++i) {
        const int j = f.slot[i];
        if (j < 0) continue;
        Eigen::Matrix<double, 6, 6> mass = Eigen::Matrix<double, 6, 6>::Zero();
        mass.topLeftCorner<3, 3>() = Mat3::Identity() / bodies.inverse_mass[i];
        mass.bottomRightCorner<3, 3>() = bodies.inverse_inertia[i].inverse();
        for (int c = 0; c < 6; ++c) {
          for (int r = 0; r <= c; ++r) values[f.position(j, r, j, c)] += mass(r, c);
        }
      }
      // Each row's blocks of J^T E^-1 J, summed over its constrained
      // components, added where they go (the block's column positions
      // looked up once). Row k's component c is, as a row of J,
      // -(f, R_a f) for a and (f, R_b f) for b, with f the frame's row c
      // and R the cross-product matrix of the arm: the blocks are those of
      // S = sum_c f f^T / E_c, e.g. a's diagonal block
      // [[S, S R_a^T], [R_a S, R_a S R_a^T]].
      using Mat6 = Eigen::Matrix<double, 6, 6>;
      const auto add = [&](int i, int j, const Mat6& block) {  // i <= j: block (i, j); i == j: its upper triangle
        const int base = f.position(i, 0, j, 0) - f.column_starts[6 * j];
        for (int c = 0; c < 6; ++c) {
          double* column = values + f.column_starts[6 * j + c] + base;
          for (int r = 0; r < (i == j ? c + 1 : 6); ++r) column[r] += block(r, c);
        }
      };
      for (size_t k = 0; k < rows.size(); ++k) {
        if (components[k] == 0) continue;
        const ContactRow& row = rows[k];
        const int a = f.slot[row.a], b = f.slot[row.b];
        const Mat3 s = row.frame.transpose() * weight[k].asDiagonal() * row.frame;
        const Mat3 ra = cross_matrix(row.arm_a), rb = cross_matrix(row.arm_b);
        const Mat3 ra_s = ra * s, rb_s = rb * s;
        Mat6 aa, bb, ab;
        aa << s, ra_s.transpose(), ra_s, ra_s * ra.transpose();
        bb << s, rb_s.transpose(), rb_s, rb_s * rb.transpose();
        ab << -s, -rb_s.transpose(), -ra_s, -ra_s * rb.transpose();
        if (a >= 0) add(a, a, aa);
        if (b >= 0) add(b, b, bb);
        if (a >= 0 && b >= 0) {
          if (a < b) add(a, b, ab);
          else add(b, a, ab.transpose());
        }
      }
      ++report.factorizations;
      if (!f.cholesky->factorize()) {
        f.usable = false;
        return -2;
      }
    }
    // dv = K^-1 J^T E^-1 r; dP = E^-1 (r - J dv), applied unprojected;
    // then again on what is left of r (iterative refinement: E's bias and
    // the round-off of a long chain of stiff contacts, which 1 / E
    // magnifies, shrink by a factor each time).
    Eigen::VectorXd rhs(6 * free_bodies), dv;
    for (int refinement = 0; refinement < kRefinements; ++refinement) {
      if (refinement > 0) {
        for (size_t k = 0; k < rows.size(); ++k) {
          if (components[k] > 0) target[k] = Vec3(rows[k].target_normal, 0.0, 0.0) - relative_velocity(rows[k], bodies);
        }
      }
      // J^T E^-1 r: per row, the impulse g = sum_c f r_c / E_c on b and
      // its opposite on a, at their arms.
      rhs.setZero();
      for (size_t k = 0; k < rows.size(); ++k) {
        if (components[k] == 0) continue;
        const ContactRow& row = rows[k];
        const int a = f.slot[row.a], b = f.slot[row.b];
        const Vec3 g = row.frame.transpose() * weight[k].cwiseProduct(target[k]);
        if (a >= 0) {
          rhs.segment<3>(6 * a) -= g;
          rhs.segment<3>(6 * a + 3) -= row.arm_a.cross(g);
        }
        if (b >= 0) {
          rhs.segment<3>(6 * b) += g;
          rhs.segment<3>(6 * b + 3) += row.arm_b.cross(g);
        }
      }
      f.cholesky->solve(rhs, dv);
      for (size_t k = 0; k < rows.size(); ++k) {
        if (components[k] == 0) continue;
        ContactRow& row = rows[k];
        const int a = f.slot[row.a], b = f.slot[row.b];
        // J dv: the change of the row's relative velocity.
        Vec3 velocity = Vec3::Zero();
        if (b >= 0) velocity += dv.segment<3>(6 * b) + dv.segment<3>(6 * b + 3).cross(row.arm_b);
        if (a >= 0) velocity -= dv.segment<3>(6 * a) + dv.segment<3>(6 * a + 3).cross(row.arm_a);
        const Vec3 moved = row.frame * velocity;
        Vec3 change = Vec3::Zero();
        for (int c = 0; c < components[k]; ++c) change[c] = (target[k][c] - moved[c]) / compliance[k][c];
        apply(row, change, bodies);
        row.impulse += change;
      }
    }
    // The impulses projected on their cones.
    int released = 0;
    for (size_t k = 0; k < rows.size(); ++k) {
      if (components[k] == 0) continue;
      ContactRow& row = rows[k];
      Vec3 p = row.impulse;
      if (p.x() < 0.0) {
        p.x() = 0.0;
        ++released;
      }
      const double limit = friction_limit(row.friction, p.x());
      const double tangential = p.tail<2>().norm();
      // A sliding point keeps sliding: its friction follows its pressure.
      if (tangential > limit || (components[k] == 1 && tangential > 0.0)) p.tail<2>() *= limit / tangential;
      const Vec3 change = p - row.impulse;
      if (change.isZero(0.0)) continue;
      apply(row, change, bodies);
      row.impulse = p;
    }
    ++report.global_steps;
    return released;
  };

  bool global_steps = settings.global_steps;
  double before_global_step = -1.0;  // the residual of the sweep before the last global step
  int worse = 0;                     // global steps that left a larger residual
  while (report.sweeps < settings.max_sweeps && groups > 0) {
    // After the first sweep (a structure at rest needs no more) and every
    // kSweepsPerGlobalStep after it.
    if (global_steps && report.sweeps % kSweepsPerGlobalStep == 1) {
      // Points the step left pulling are released, and the step taken
      // again without them, a few times at most.
      int released = global_step();
      for (int again = 1; again < kGlobalStepRepeats && released > 0; ++again) released = global_step();
      global_steps = released != -2;
      before_global_step = released >= 0 ? report.residual : -1.0;
    }
    ++report.sweeps;
    double largest_residual = 0.0;
    int worst = -1;
    // Symmetric Gauss-Seidel over the groups: forward and backward in turn,
    // so that what one end of the order learns reaches the other in one
    // sweep pair. Each group (the points of one contact between two
    // blocks) is solved to the tolerance, or kGroupPasses passes, before
    // the next: a stack's weight then goes down it in one sweep.
    const bool forward = report.sweeps % 2 == 1;
    for (size_t visit = 0; visit < groups; ++visit) {
      const size_t g = forward ? visit : groups - 1 - visit;
      const size_t begin = group_start[g], end = group_start[g + 1];
      int group_worst = -1;
      double group_residual = pass(begin, end, group_worst);
      if (group_residual > largest_residual) {
        largest_residual = group_residual;
        worst = group_worst;
      }
      for (int inner = 1; inner < kGroupPasses && group_residual > 0.5 * settings.velocity_tolerance; ++inner) {
        group_residual = pass(begin, end, group_worst);
      }
    }
    // Global steps that made things worse kGlobalStepsWorse times are not
    // taken again: the sweeps finish the solve.
    if (before_global_step >= 0.0 && report.sweeps % kSweepsPerGlobalStep == 2 &&
        largest_residual > before_global_step && ++worse == kGlobalStepsWorse) {
      global_steps = false;
    }
    report.residual = largest_residual;
    report.worst_row = worst;
    if (largest_residual <= settings.velocity_tolerance) {
      report.converged = true;
      break;
    }
    // Sweeps that stall (the load cycling between redundant or sliding
    // points) are finished by Newton's method; the sweeps after it judge
    // its answer by the same test.
    if (settings.newton_after_sweeps > 0 && report.sweeps % settings.newton_after_sweeps == 0 &&
        largest_residual <= kNewtonFrom * settings.velocity_tolerance) {
      report.newton_iterations +=
          solve_contact_newton(rows, bodies, kNewtonTolerance * settings.velocity_tolerance, kNewtonIterations).iterations;
    }
  }
  if (groups == 0) report.converged = true;
  return report;
}

}  // namespace ashlar
