#include "dynamics/contact_solver.hpp"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <utility>

#include "core/parallel_loop.hpp"
#include "core/sparse_cholesky.hpp"
#include "dynamics/body_blocks.hpp"
#include "dynamics/contact_interior.hpp"

namespace ashlar {
namespace {

// Most passes over one group's rows per sweep.
constexpr int kGroupPasses = 10;
// A row whose residual is at most this fraction of the tolerance is left
// as it is by the sweeps, and a group whose rows all were at its last
// pass, and whose blocks nothing has moved since, is passed over (its
// residual is the same). After a shaken wall's global step most groups
// are settled: the sweeps took 0.39 s of its 0.1 s against 0.82 s. Small
// changes of settled rows also no longer keep the load cycling among the
// redundant corners of a face: the Armadillo vault's first step from
// zero impulses converges (it stopped at max_sweeps at 1.4e-5 m/s).
// 0.25 left a wall at rest taking 0.66 global steps a step (0.08).
constexpr double kSettled = 0.1;
// Sweeps between two global steps of one solve. The sweeps after a global
// step mostly pass over settled groups, so a global step costs about as
// much as fifteen of them on a wall: on the 1,006-block wall shaken, 6 took
// 11.6 sweeps and 2.62 global steps a step (the solves 2.28 s of 0.1 s), 4
// took 10.8 and 3.18 (2.88 s), 8 took 11.7 and 2.72.
constexpr int kSweepsPerGlobalStep = 6;
// Global steps in a row at most, each without the points the one before
// left pulling.
constexpr int kGlobalStepRepeats = 2;
// A solve stops taking global steps once this many left a larger residual
// than the sweep before them.
constexpr int kGlobalStepsWorse = 3;
// A global step is not taken where the sweeps since the last would, at
// the rate the residual fell over the last two, reach the tolerance in at
// most this many more. On the 1,006-block wall shaken (figures from
// before sweeps passed over settled groups, with four sweeps between
// global steps): 7.1 sweeps and 3.68 global steps a step without it, 8.7
// and 2.44 with 8; 16 took 8.7 and 2.20, but left the wall at rest with
// 0.55 global steps a step instead of 0.08 (a step finished by sweeps just
// below the tolerance leaves the next a worse start than one a global step
// finished). Once that many sweeps have passed since the first global step
// skipped and the solve has not finished, the guess was wrong (a
// collapse's hard steps, where the residual falls fast for a few sweeps,
// then stalls), and the solve takes every global step from then on: six
// arch collapses (16-24 voussoirs, 8,700 steps) left 683 steps unconverged
// when the guess was never checked, 584 with this, 545 without skipping;
// the shaken wall 8.7 sweeps and 2.60 global steps a step.
constexpr double kSweepsAhead = 8.0;
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
// Rows from which a solve is split over the threads: below it a wake-up
// of the helper threads costs more than the pass it would share (a sweep
// over 2,000 rows takes about 0.2 ms).
constexpr int kParallelRows = 2000;
// Cone programs of the interior-point method's fixed point at most
// (contact_interior.hpp). On the 106-block wall shaken at 1.5 g for 0.1 s,
// 3 of 48 calls reached 30 (14-20 on most).
constexpr int kInteriorRounds = 30;

// Adds a row's impulse (local frame) to the velocities of its bodies for
// which moves(body) is true. A fixed body is never written (it would only
// gain zeros), so that threads sweeping rows of different bodies on one
// support never write the same memory.
template <typename Moves>
void apply_to(const ContactRow& row, const Vec3& local_impulse, BodyVelocities& bodies, const Moves& moves) {
  const Vec3 p = row.frame.transpose() * local_impulse;
  if (bodies.inverse_mass[row.b] > 0.0 && moves(row.b)) {
    bodies.linear[row.b] += bodies.inverse_mass[row.b] * p;
    bodies.angular[row.b] += bodies.inverse_inertia[row.b] * row.arm_b.cross(p);
  }
  if (bodies.inverse_mass[row.a] > 0.0 && moves(row.a)) {
    bodies.linear[row.a] -= bodies.inverse_mass[row.a] * p;
    bodies.angular[row.a] -= bodies.inverse_inertia[row.a] * row.arm_a.cross(p);
  }
}

void apply(const ContactRow& row, const Vec3& local_impulse, BodyVelocities& bodies) {
  apply_to(row, local_impulse, bodies, [](int) { return true; });
}

// The radius of the friction disc, mu P_n (0 when P_n is, whatever mu).
double friction_limit(double friction, double normal) {
  return normal > 0.0 ? friction * normal : 0.0;
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

// A solve split over threads: the free bodies in `parts` parts of about
// equal numbers of rows, cut so that few rows link two parts and no cut
// runs across the load path (the caller's order: from the top down). A
// structure wider than tall (a wall, a vault) is cut into runs of a
// breadth-first order from a far end: slabs across its length. One
// taller than wide (a tower) is cut by planes along the order's axis
// (found from the joints' points), across its width: its breadth-first
// slabs would be its top and bottom halves, and a 10 x 30 grid of blocks
// cut so took 16 times the sweeps of one thread (11 cut along its
// height). A group whose free bodies are all in one part is that part's;
// the few that link two parts are shared. A part's thread writes the
// velocities of its own bodies only.
struct BodySplit {
  int parts = 1;
  std::vector<int> part_of;                 // body -> its part, -1 for a fixed body
  std::vector<std::vector<int>> groups;     // per part: its groups, in the caller's order
  std::vector<int> shared;                  // groups linking two parts, in the caller's order
  std::vector<std::vector<int>> rows;       // per part: the rows at its bodies, ascending
  // The part that writes row k's impulse in passes over the parts' rows.
  int owner(const ContactRow& row) const { return part_of[row.b] >= 0 ? part_of[row.b] : part_of[row.a]; }
};

// groups: the groups' first rows, and the end of the rows last.
BodySplit split_bodies(const std::vector<ContactRow>& rows, const std::vector<size_t>& group_start,
                       const BodyVelocities& bodies, int parts) {
  const int n = static_cast<int>(bodies.inverse_mass.size());
  const size_t groups = rows.empty() ? 0 : group_start.size() - 1;
  BodySplit split;
  split.parts = parts;
  split.part_of.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    if (bodies.inverse_mass[i] > 0.0) split.part_of[i] = 0;
  }
  if (parts > 1) {
    // The bodies' centroids, up to a shift per connected piece, from the
    // rows' arms (a row's point is each body's centroid plus its arm),
    // breadth-first over the groups; and each free body's rows.
    std::vector<int> weight(n, 0), first(n + 1, 0);
    for (size_t g = 0; g < groups; ++g) {
      const ContactRow& row = rows[group_start[g]];
      const int count = static_cast<int>(group_start[g + 1] - group_start[g]);
      if (split.part_of[row.a] >= 0) weight[row.a] += count;
      if (split.part_of[row.b] >= 0) weight[row.b] += count;
      ++first[row.a + 1];
      ++first[row.b + 1];
    }
    for (int i = 0; i < n; ++i) first[i + 1] += first[i];
    std::vector<int> linked(first[n]), next(first.begin(), first.end() - 1);
    for (size_t g = 0; g < groups; ++g) {
      const ContactRow& row = rows[group_start[g]];
      linked[next[row.a]++] = static_cast<int>(g);
      linked[next[row.b]++] = static_cast<int>(g);
    }
    std::vector<Vec3> centroid(n, Vec3::Zero());
    std::vector<char> placed(n, 0);
    std::vector<int> queue;
    for (int root = 0; root < n; ++root) {
      if (placed[root] || first[root] == first[root + 1]) continue;
      placed[root] = 1;
      queue.assign(1, root);
      for (size_t q = 0; q < queue.size(); ++q) {
        const int i = queue[q];
        for (int e = first[i]; e < first[i + 1]; ++e) {
          const ContactRow& row = rows[group_start[linked[e]]];
          const int j = row.a == i ? row.b : row.a;
          if (placed[j]) continue;
          placed[j] = 1;
          const Vec3 point = centroid[i] + (row.a == i ? row.arm_a : row.arm_b);
          centroid[j] = point - (row.a == j ? row.arm_a : row.arm_b);
          queue.push_back(j);
        }
      }
    }
    // The order's axis: the one along which the joints' points follow the
    // caller's order most closely (the largest correlation of a point's
    // coordinate with its joint's place in the order; along gravity for
    // an order from the top down).
    Vec3 mean = Vec3::Zero();
    for (size_t g = 0; g < groups; ++g) mean += centroid[rows[group_start[g]].a] + rows[group_start[g]].arm_a;
    mean /= static_cast<double>(groups);
    const double middle = 0.5 * static_cast<double>(groups - 1);
    Vec3 covariance = Vec3::Zero(), spread = Vec3::Zero();
    for (size_t g = 0; g < groups; ++g) {
      const Vec3 d = centroid[rows[group_start[g]].a] + rows[group_start[g]].arm_a - mean;
      covariance += (static_cast<double>(g) - middle) * d;
      spread += d.cwiseProduct(d);
    }
    Vec3 along = Vec3::Zero();
    for (int axis = 0; axis < 3; ++axis) {
      if (spread[axis] > 0.0) along[axis] = std::abs(covariance[axis]) / std::sqrt(spread[axis]);
    }
    int order_axis = -1;
    along.maxCoeff(&order_axis);
    if (!(along[order_axis] > 0.0)) order_axis = -1;
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity()), high = -low;
    std::vector<int> cut;
    for (int i = 0; i < n; ++i) {
      if (weight[i] == 0) continue;
      cut.push_back(i);
      low = low.cwiseMin(centroid[i]);
      high = high.cwiseMax(centroid[i]);
    }
    int longest = 0;
    (high - low).maxCoeff(&longest);
    if (longest != order_axis) {
      // Wider than tall: breadth-first from a far end of each connected
      // piece of free bodies (from the body last reached from its first
      // body), cut into runs (slabs across a wall's length: on walls this
      // took fewer sweeps than the plane cut below).
      std::vector<int> mark(n, 0), order;
      int stamp = 0;
      const auto free = [&](int body) { return split.part_of[body] >= 0; };
      const auto reach = [&](int root) {
        queue.assign(1, root);
        mark[root] = ++stamp;
        for (size_t q = 0; q < queue.size(); ++q) {
          const int i = queue[q];
          for (int e = first[i]; e < first[i + 1]; ++e) {
            const ContactRow& row = rows[group_start[linked[e]]];
            const int j = row.a == i ? row.b : row.a;
            if (free(j) && mark[j] != stamp) {
              mark[j] = stamp;
              queue.push_back(j);
            }
          }
        }
      };
      std::fill(placed.begin(), placed.end(), 0);
      for (int i : cut) {  // ascending
        if (placed[i]) continue;
        reach(i);
        reach(queue.back());
        for (int j : queue) {
          placed[j] = 1;
          order.push_back(j);
        }
      }
      cut.swap(order);
    } else {
      // Taller than wide: by the centroids along the longest axis across
      // the order's.
      int axis = -1;
      for (int candidate = 0; candidate < 3; ++candidate) {
        if (candidate != order_axis && (axis < 0 || high[candidate] - low[candidate] > high[axis] - low[axis])) {
          axis = candidate;
        }
      }
      std::sort(cut.begin(), cut.end(), [&](int x, int y) {
        return centroid[x][axis] < centroid[y][axis] || (centroid[x][axis] == centroid[y][axis] && x < y);
      });
    }
    long long total = 0, before = 0;
    for (int j : cut) total += weight[j];
    for (int j : cut) {
      split.part_of[j] = static_cast<int>(std::min<long long>(parts - 1, before * parts / std::max(total, 1LL)));
      before += weight[j];
    }
  }
  split.groups.assign(parts, {});
  split.rows.assign(parts, {});
  for (size_t g = 0; g < groups; ++g) {
    const int a = split.part_of[rows[group_start[g]].a], b = split.part_of[rows[group_start[g]].b];
    if (a < 0 || b < 0 || a == b) split.groups[std::max(a, b)].push_back(static_cast<int>(g));
    else split.shared.push_back(static_cast<int>(g));
  }
  for (size_t k = 0; k < rows.size(); ++k) {
    const int a = split.part_of[rows[k].a], b = split.part_of[rows[k].b];
    if (a >= 0) split.rows[a].push_back(static_cast<int>(k));
    if (b >= 0 && b != a) split.rows[b].push_back(static_cast<int>(k));
  }
  return split;
}

}  // namespace

// The global step's factorisation and the active set's pattern it was made
// for. Unknowns: 6 per free body (velocity, then angular velocity), free
// bodies in index order.
struct ContactSolver::Factor {
  std::vector<int> slot;                      // body -> its free-body number, -1 fixed
  std::vector<std::pair<int, int>> links;     // free-body numbers (i < j) linked by a constrained row, sorted
  BodyBlocks blocks;
  std::unique_ptr<SparseCholesky> cholesky;
  SparseCholeskyOptions options;  // whole on one thread
  bool usable = false;

  void set_pattern(int free_bodies, std::vector<std::pair<int, int>> linked) {
    links = std::move(linked);
    std::vector<int> rows = blocks.set(free_bodies, links);
    options.block_rows = 6;  // BodyBlocks' 6 x 6 blocks
    cholesky = std::make_unique<SparseCholesky>(6 * free_bodies, blocks.column_starts(), std::move(rows), options);
  }
};

Vec3 relative_velocity(const ContactRow& row, const BodyVelocities& bodies) {
  const Vec3 vb = bodies.linear[row.b] + bodies.angular[row.b].cross(row.arm_b);
  const Vec3 va = bodies.linear[row.a] + bodies.angular[row.a].cross(row.arm_a);
  return row.frame * (vb - va);
}

double row_residual(const ContactRow& row, const Vec3& u) {
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

RowConstants row_constants(const ContactRow& row, const BodyVelocities& bodies) {
  Mat3 w = Mat3::Zero();
  const auto add = [&](int body, const Vec3& arm) {
    const Mat3 rx = cross_matrix(arm);
    w += bodies.inverse_mass[body] * Mat3::Identity() - rx * bodies.inverse_inertia[body] * rx;
  };
  add(row.a, row.arm_a);
  add(row.b, row.arm_b);
  w = row.frame * w * row.frame.transpose();
  const Eigen::Matrix2d wt = w.bottomRightCorner<2, 2>();
  const double largest = 0.5 * (wt.trace() + std::hypot(wt(0, 0) - wt(1, 1), 2.0 * wt(0, 1)));
  return {1.0 / w(0, 0), 1.0 / largest, w.diagonal()};
}

// The per-row buffers of a solve (see solve()).
struct ContactSolver::Workspace {
  std::vector<RowConstants> constants;
  std::vector<int> components;  // the global step's components held
  std::vector<Vec3> target, compliance, weight, change;
  std::vector<double> most;     // per body
  std::vector<Mat3> inertia;    // per body: its inertia (kg m^2), world frame
  Eigen::VectorXd weighted;     // per free body's 6 unknowns: the solves' dv, weighted
  std::vector<char> settled, shared_group;   // per group
  std::vector<int> groups_at_start, groups_at;  // per body: its groups
};

ContactSolver::ContactSolver(int threads)
    : factor_(std::make_unique<Factor>()),
      work_(std::make_unique<Workspace>()),
      loop_(std::make_unique<ParallelLoop>(threads > 0 ? std::min(threads, ParallelLoop::kMaxThreads) : 0,
                                           kParallelRows)) {
  if (loop_->parts() == 1) factor_->options.split_from_rows = INT_MAX;
}
ContactSolver::~ContactSolver() = default;

Mat3 cross_matrix(const Vec3& r) {
  Mat3 m;
  m << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
  return m;
}

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
  ParallelLoop& loop = *loop_;
  const int row_count = static_cast<int>(rows.size());
  // Groups: runs of consecutive rows between the same two bodies.
  std::vector<size_t> group_start{0};
  for (size_t k = 1; k < rows.size(); ++k) {
    if (rows[k].a != rows[k - 1].a || rows[k].b != rows[k - 1].b) group_start.push_back(k);
  }
  group_start.push_back(rows.size());
  const size_t groups = rows.empty() ? 0 : group_start.size() - 1;
  const BodySplit split = split_bodies(rows, group_start, bodies, loop.parts_for(row_count));
  // The groups at each free body (shared ones left out: they are measured
  // in every sweep; a fixed body never moves, so it has none), and which
  // groups the sweeps may pass over (see kSettled): none yet.
  Workspace& work = *work_;
  std::vector<char>& settled = work.settled;
  std::vector<char>& shared_group = work.shared_group;
  std::vector<int>& groups_at_start = work.groups_at_start;
  std::vector<int>& groups_at = work.groups_at;
  settled.assign(groups, 0);
  shared_group.assign(groups, 0);
  for (const int g : split.shared) shared_group[g] = 1;
  groups_at_start.assign(bodies.inverse_mass.size() + 1, 0);
  const auto free = [&](int body) { return bodies.inverse_mass[body] > 0.0; };
  for (size_t g = 0; g < groups; ++g) {
    if (shared_group[g]) continue;
    for (const int body : {rows[group_start[g]].a, rows[group_start[g]].b}) {
      if (free(body)) ++groups_at_start[body + 1];
    }
  }
  for (size_t i = 0; i < bodies.inverse_mass.size(); ++i) groups_at_start[i + 1] += groups_at_start[i];
  groups_at.resize(groups_at_start.back());
  {
    std::vector<int> next(groups_at_start.begin(), groups_at_start.end() - 1);
    for (size_t g = 0; g < groups; ++g) {
      if (shared_group[g]) continue;
      for (const int body : {rows[group_start[g]].a, rows[group_start[g]].b}) {
        if (free(body)) groups_at[next[body]++] = static_cast<int>(g);
      }
    }
  }
  // Work on each row alone, the rows in contiguous parts on the threads.
  const auto each_row = [&](const auto& per_row) {
    loop.run(row_count, [&](int begin, int end, int) {
      for (int k = begin; k < end; ++k) per_row(k);
    });
  };
  // Work on each part's bodies, each part on its thread: per_part(part).
  const auto each_part = [&](const auto& per_part) { loop.run_parts(split.parts, per_part); };
  // A row's impulse (local frame) added to the velocities of the part's
  // bodies: a pass over every part's rows adds, to each body, its rows'
  // impulses in the rows' order, as one thread would.
  const auto apply_in_part = [&](const ContactRow& row, const Vec3& local_impulse, int part) {
    apply_to(row, local_impulse, bodies, [&](int body) { return split.part_of[body] == part; });
  };

  // Per-row buffers kept from solve to solve (resized, not cleared: each
  // pass writes a row's entries before any reads them), so that a step
  // allocates (and the system maps and clears) none of them anew.
  std::vector<RowConstants>& constants = work.constants;
  constants.resize(rows.size());
  each_row([&](int k) {
    constants[k] = row_constants(rows[k], bodies);
    // The warm start, clipped to the cone (the friction may have changed).
    Vec3& p = rows[k].impulse;
    p.x() = std::max(0.0, p.x());
    const double limit = friction_limit(rows[k].friction, p.x());
    const double tangential = p.tail<2>().norm();
    if (tangential > limit) p.tail<2>() *= limit / tangential;
  });
  each_part([&](int part) {
    for (int k : split.rows[part]) apply_in_part(rows[k], rows[k].impulse, part);
  });
  ContactSolverReport report;

  // One pass over rows [begin, end): each row's local update; returns the
  // largest residual met, and where (worst).
  const double settled_residual = kSettled * settings.velocity_tolerance;
  const auto pass = [&](size_t begin, size_t end, int& worst, bool& changed) {
    double largest = 0.0;
    for (size_t k = begin; k < end; ++k) {
      ContactRow& row = rows[k];
      const RowConstants& c = constants[k];
      const Vec3 u = relative_velocity(row, bodies);
      const double r = row_residual(row, u);
      if (r > largest) {
        largest = r;
        worst = static_cast<int>(k);
      }
      if (r <= settled_residual) continue;
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
      changed = true;
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
  // Per row: the components held, r, the compliance, its inverse; per
  // part: sums; the impulses' changes of the projection.
  std::vector<int>& components = work.components;
  std::vector<Vec3>& target = work.target;
  std::vector<Vec3>& compliance = work.compliance;
  std::vector<Vec3>& weight = work.weight;
  std::vector<Vec3>& change = work.change;
  components.resize(rows.size());
  target.resize(rows.size());
  compliance.resize(rows.size());
  weight.resize(rows.size());
  change.resize(rows.size());
  std::vector<int> part_count(loop.parts());
  // Passes over the parts' rows compute what a row needs where they meet
  // it (a row of two parts twice, the same way) and only the row's owner
  // (split.owner) stores it, so that no pass reads what another thread
  // writes: one wake-up of the threads per pass.
  std::vector<double>& most = work.most;
  most.resize(bodies.inverse_mass.size());
  work.inertia.resize(bodies.inverse_mass.size());
  const auto global_step = [&]() {
    if (free_bodies < 0) set_up_pattern();
    // The components held and r; the largest normal impulse at each body.
    std::fill(most.begin(), most.end(), 0.0);
    each_part([&](int part) {
      int constrained = 0;
      for (int k : split.rows[part]) {
        const ContactRow& row = rows[k];
        if (split.owner(row) == part) {
          const Vec3 u = relative_velocity(row, bodies);
          components[k] = constrained_components(row, u, settings.velocity_tolerance);
          target[k] = Vec3(row.target_normal, 0.0, 0.0) - u;
          constrained += components[k];
        }
        for (const int body : {row.a, row.b}) {
          if (split.part_of[body] == part) most[body] = std::max(most[body], row.impulse.x());
        }
      }
      part_count[part] = constrained;
    });
    int constrained = 0;
    for (int part = 0; part < split.parts; ++part) constrained += part_count[part];
    if (constrained == 0) return -1;
    // Row k's E, and 1 / E per component (0 for those not held), into c
    // and w.
    const auto row_compliance = [&](int k, Vec3& c, Vec3& w) {
      w.setZero();
      if (components[k] == 0) return;
      const double p = rows[k].impulse.x();
      const double reference = std::max(f.slot[rows[k].a] >= 0 ? most[rows[k].a] : 0.0,
                                        f.slot[rows[k].b] >= 0 ? most[rows[k].b] : 0.0);
      const double spread = p > 0.0 ? std::clamp(reference / p, 1.0, kMostSpread) : reference > 0.0 ? kMostSpread : 1.0;
      c = kCompliance * spread * constants[k].diagonal;
      for (int component = 0; component < components[k]; ++component) w[component] = 1.0 / c[component];
    };
    // A new factorisation each step: E follows the impulses, and a
    // factorisation made for another E would give dP = E^-1 (r - J dv)
    // from a dv that does not belong to it (a stale one was tried: its
    // error, scaled by 1 / E, blew up shaken walls).
    // The bodies' right-hand side J^T E^-1 r (see below), first filled
    // with the matrix.
    Eigen::VectorXd rhs(6 * free_bodies), dv;
    // J^T E^-1 r's terms of row k for the part's own bodies: the impulse
    // g = sum_c f r_c / E_c (w = 1 / E) on b and its opposite on a, at
    // their arms.
    const auto add_rhs = [&](int k, const Vec3& r, const Vec3& w, int part) {
      const ContactRow& row = rows[k];
      const Vec3 g = row.frame.transpose() * w.cwiseProduct(r);
      if (split.part_of[row.a] == part) {
        rhs.segment<3>(6 * f.slot[row.a]) -= g;
        rhs.segment<3>(6 * f.slot[row.a] + 3) -= row.arm_a.cross(g);
      }
      if (split.part_of[row.b] == part) {
        rhs.segment<3>(6 * f.slot[row.b]) += g;
        rhs.segment<3>(6 * f.slot[row.b] + 3) += row.arm_b.cross(g);
      }
    };
    {
      // Each part fills the columns of its own bodies: their mass, then
      // each of its groups' blocks of J^T E^-1 J in the groups' order (as
      // one thread would), summed over the group's rows and each row's
      // constrained components. Row
      // k's component c is, as a row of J, -(f, R_a f) for a and
      // (f, R_b f) for b, with f the frame's row c and R the cross-product
      // matrix of the arm: the blocks are those of S = sum_c f f^T / E_c,
      // e.g. a's diagonal block [[S, S R_a^T], [R_a S, R_a S R_a^T]]. The
      // block of two bodies goes in the column of the later one.
      double* values = f.cholesky->values();
      using Mat6 = Eigen::Matrix<double, 6, 6>;
      const auto add = [&](int i, int j, const Mat6& block) { f.blocks.add(values, i, j, block); };
      each_part([&](int part) {
        for (size_t i = 0; i < bodies.inverse_mass.size(); ++i) {
          if (split.part_of[i] != part) continue;
          const int j = f.slot[i];
          f.blocks.clear_column(values, j);
          rhs.segment<6>(6 * j).setZero();
          Mat6 mass = Mat6::Zero();
          mass.topLeftCorner<3, 3>() = Mat3::Identity() / bodies.inverse_mass[i];
          work.inertia[i] = bodies.inverse_inertia[i].inverse();
          mass.bottomRightCorner<3, 3>() = work.inertia[i];
          add(j, j, mass);
        }
        // The rows of one group (consecutive in the part's list: they link
        // the same two bodies) are summed before their blocks are added.
        const std::vector<int>& list = split.rows[part];
        Mat3 sum_s = Mat3::Zero(), sum_ra_s = Mat3::Zero(), sum_rb_s = Mat3::Zero(), sum_ra_s_ra = Mat3::Zero(),
             sum_rb_s_rb = Mat3::Zero(), sum_ra_s_rb = Mat3::Zero();
        bool pending = false;
        for (size_t e = 0; e < list.size(); ++e) {
          const int k = list[e];
          const ContactRow& row = rows[k];
          const bool own_a = split.part_of[row.a] == part, own_b = split.part_of[row.b] == part;
          const int a = f.slot[row.a], b = f.slot[row.b];
          // The block of the two bodies, in this part's column.
          const bool own_ab = a >= 0 && b >= 0 && ((a < b && own_b) || (b < a && own_a));
          if (components[k] != 0) {
            Vec3 row_weight, row_compliance_of;
            row_compliance(k, row_compliance_of, row_weight);
            if (split.owner(row) == part) {
              compliance[k] = row_compliance_of;
              weight[k] = row_weight;
            }
            add_rhs(k, target[k], row_weight, part);
            Mat3 s = Mat3::Zero();
            for (int c = 0; c < components[k]; ++c) {
              s.noalias() += row_weight[c] * row.frame.row(c).transpose() * row.frame.row(c);
            }
            const Mat3 ra = cross_matrix(row.arm_a), rb = cross_matrix(row.arm_b);
            const Mat3 ra_s = ra * s, rb_s = rb * s;
            if (!pending) {
              sum_s.setZero();
              sum_ra_s.setZero();
              sum_rb_s.setZero();
              sum_ra_s_ra.setZero();
              sum_rb_s_rb.setZero();
              sum_ra_s_rb.setZero();
              pending = true;
            }
            sum_s += s;
            sum_ra_s += ra_s;
            sum_rb_s += rb_s;
            if (own_a) sum_ra_s_ra.noalias() += ra_s * ra.transpose();
            if (own_b) sum_rb_s_rb.noalias() += rb_s * rb.transpose();
            if (own_ab) sum_ra_s_rb.noalias() += ra_s * rb.transpose();
          }
          const bool group_ends =
              e + 1 == list.size() || rows[list[e + 1]].a != row.a || rows[list[e + 1]].b != row.b;
          if (!group_ends || !pending) continue;
          pending = false;
          Mat6 block;
          if (own_a) {
            block << sum_s, sum_ra_s.transpose(), sum_ra_s, sum_ra_s_ra;
            add(a, a, block);
          }
          if (own_b) {
            block << sum_s, sum_rb_s.transpose(), sum_rb_s, sum_rb_s_rb;
            add(b, b, block);
          }
          if (own_ab) {
            block << -sum_s, -sum_rb_s.transpose(), -sum_ra_s, -sum_ra_s_rb;
            if (a < b) add(a, b, block);
            else add(b, a, block.transpose());
          }
        }
      });
      ++report.factorizations;
      if (!f.cholesky->factorize()) {
        f.usable = false;
        return -2;
      }
    }
    // dv = K^-1 J^T E^-1 r; dP = E^-1 (r - J dv); then again on what is
    // left of r (iterative refinement: E's bias shrinks by a factor each
    // time). No pass over the rows is needed between the solves: applied,
    // dP changes the bodies' velocities by M^-1 J^T dP = dv (from K dv =
    // J^T E^-1 r), so what is left is r - J dv, and the next right-hand
    // side J^T E^-1 (r - J dv) = M dv. Over n solves the impulses change by
    // E^-1 times the sum of what each leaves, E^-1 (n r - J sum_i (n - i)
    // dv_i) (i from 0), applied in one pass.
    Eigen::VectorXd& weighted = work.weighted;
    weighted.setZero(6 * free_bodies);
    for (int refinement = 0; refinement < kRefinements; ++refinement) {
      f.cholesky->solve(rhs, dv);
      weighted += static_cast<double>(kRefinements - refinement) * dv;
      if (refinement + 1 == kRefinements) break;
      for (size_t i = 0; i < bodies.inverse_mass.size(); ++i) {
        const int j = f.slot[i];
        if (j < 0) continue;
        rhs.segment<3>(6 * j) = dv.segment<3>(6 * j) / bodies.inverse_mass[i];
        rhs.segment<3>(6 * j + 3) = work.inertia[i] * dv.segment<3>(6 * j + 3);
      }
    }
    each_part([&](int part) {
      for (int k : split.rows[part]) {
        if (components[k] == 0) continue;
        ContactRow& row = rows[k];
        const int a = f.slot[row.a], b = f.slot[row.b];
        // J sum_i (n - i) dv_i: the row's relative velocity changes so summed.
        Vec3 velocity = Vec3::Zero();
        if (b >= 0) velocity += weighted.segment<3>(6 * b) + weighted.segment<3>(6 * b + 3).cross(row.arm_b);
        if (a >= 0) velocity -= weighted.segment<3>(6 * a) + weighted.segment<3>(6 * a + 3).cross(row.arm_a);
        const Vec3 moved = row.frame * velocity;
        Vec3 impulse = Vec3::Zero();
        for (int c = 0; c < components[k]; ++c) impulse[c] = (kRefinements * target[k][c] - moved[c]) / compliance[k][c];
        apply_in_part(row, impulse, part);
        if (split.owner(row) == part) row.impulse += impulse;
      }
    });
    // The impulses projected on their cones.
    loop.run(row_count, [&](int begin, int end, int part) {
      int released = 0;
      for (int k = begin; k < end; ++k) {
        change[k].setZero();
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
        change[k] = p - row.impulse;
        if (!change[k].isZero(0.0)) row.impulse = p;
      }
      part_count[part] = released;
    });
    int released = 0;
    for (int part = 0; part < loop.parts_for(row_count); ++part) released += part_count[part];
    each_part([&](int part) {
      for (int k : split.rows[part]) {
        if (!change[k].isZero(0.0)) apply_in_part(rows[k], change[k], part);
      }
    });
    ++report.global_steps;
    return released;
  };

  // A sweep over some groups, in the caller's order or back: its largest
  // residual and where, from `largest` and `worst` up.
  const auto sweep = [&](const std::vector<int>& list, bool forward, double& largest, int& worst) {
    const size_t count = list.size();
    for (size_t visit = 0; visit < count; ++visit) {
      const size_t g = list[forward ? visit : count - 1 - visit];
      if (settled[g]) continue;
      const size_t begin = group_start[g], end = group_start[g + 1];
      int group_worst = -1;
      bool changed = false, last_changed = false;
      double group_residual = pass(begin, end, group_worst, last_changed);
      if (group_residual > largest) {
        largest = group_residual;
        worst = group_worst;
      }
      for (int inner = 1; inner < kGroupPasses && group_residual > 0.5 * settings.velocity_tolerance; ++inner) {
        changed = changed || last_changed;
        last_changed = false;
        group_residual = pass(begin, end, group_worst, last_changed);
      }
      changed = changed || last_changed;
      settled[g] = !last_changed && group_residual <= settled_residual && !shared_group[g];
      if (!changed) continue;
      // Its blocks moved: the groups at them are measured again.
      for (const int body : {rows[begin].a, rows[begin].b}) {
        for (int e = groups_at_start[body]; e < groups_at_start[body + 1]; ++e) settled[groups_at[e]] = 0;
      }
    }
  };
  std::vector<double> part_largest(split.parts);
  std::vector<int> part_worst(split.parts);

  // The interior-point method's shift, kept from call to call within the
  // solve: a later call goes on with the fixed point where the last left
  // it. The 106-block wall at 1.5 g for 0.2 s: 2 steps unconverged, 130 s,
  // against 19 and 149 s starting every call from zero; the six arches
  // 11.0 s against 13.1.
  std::vector<double> shift;
  bool global_steps = settings.global_steps;
  double before_global_step = -1.0;  // the residual of the sweep before the last global step
  int worse = 0;                     // global steps that left a larger residual
  std::array<double, 3> residuals{};  // of the last three sweeps, the last last
  int first_skip = -1;  // the sweep at which a global step was first skipped (sweeps_finish below)
  while (report.sweeps < settings.max_sweeps && groups > 0) {
    // After the first sweep (a structure at rest needs no more) and every
    // kSweepsPerGlobalStep after it.
    // Not when the sweeps converge fast enough to finish within
    // kSweepsAhead more (the residual falling at the first of the last two
    // sweeps, and its fall per sweep over both extrapolated).
    const auto sweeps_finish = [&]() {
      if (report.sweeps < 3 || !(residuals[1] < residuals[0])) return false;
      const double rate = std::sqrt(residuals[2] / residuals[0]);
      return rate < 1.0 && std::log(settings.velocity_tolerance / residuals[2]) / std::log(rate) <= kSweepsAhead;
    };
    if (global_steps && report.sweeps % kSweepsPerGlobalStep == 1) {
      // Sweeps that did not finish within kSweepsAhead of the first skip
      // were a wrong guess: this solve takes every global step from then on.
      const bool guess = first_skip < 0 || report.sweeps - first_skip < kSweepsAhead;
      if (guess && sweeps_finish()) {
        if (first_skip < 0) first_skip = report.sweeps;
      } else {
        // Points the step left pulling are released, and the step taken
        // again without them, a few times at most.
        int released = global_step();
        for (int again = 1; again < kGlobalStepRepeats && released > 0; ++again) released = global_step();
        global_steps = released != -2;
        std::fill(settled.begin(), settled.end(), 0);
        before_global_step = released >= 0 ? report.residual : -1.0;
      }
    }
    ++report.sweeps;
    // Symmetric Gauss-Seidel over the groups: forward and backward in turn,
    // so that what one end of the order learns reaches the other in one
    // sweep pair. Each group (the points of one contact between two
    // blocks) is solved to the tolerance, or kGroupPasses passes, before
    // the next: a stack's weight then goes down it in one sweep. Split,
    // each part sweeps its own groups on its thread, and the shared ones
    // are swept after them (forward) or before (backward): the same as one
    // thread sweeping the parts' groups one part after another.
    const bool forward = report.sweeps % 2 == 1;
    const auto sweep_parts = [&]() {
      each_part([&](int part) {
        part_largest[part] = 0.0;
        part_worst[part] = -1;
        sweep(split.groups[part], forward, part_largest[part], part_worst[part]);
      });
    };
    double largest_residual = 0.0;
    int worst = -1;
    if (!forward) sweep(split.shared, forward, largest_residual, worst);
    sweep_parts();
    if (forward) sweep(split.shared, forward, largest_residual, worst);
    for (int part = 0; part < split.parts; ++part) {
      if (part_largest[part] > largest_residual) {
        largest_residual = part_largest[part];
        worst = part_worst[part];
      }
    }
    // Global steps that made things worse kGlobalStepsWorse times are not
    // taken again: the sweeps finish the solve.
    if (before_global_step >= 0.0 && report.sweeps % kSweepsPerGlobalStep == 2 &&
        largest_residual > before_global_step && ++worse == kGlobalStepsWorse) {
      global_steps = false;
    }
    report.residual = largest_residual;
    residuals = {residuals[1], residuals[2], largest_residual};
    report.worst_row = worst;
    if (largest_residual <= settings.velocity_tolerance) {
      report.converged = true;
      break;
    }
    // Sweeps that stall (the load cycling between redundant points, or
    // between points sliding at their friction limit, or a mechanism of
    // many blocks moving at once) are finished by the interior-point
    // method; the sweeps after it judge its answer by the same test.
    if (settings.interior_after_sweeps > 0 && report.sweeps % settings.interior_after_sweeps == 0) {
      const ContactInteriorReport interior =
          solve_contact_interior(rows, bodies, settings.velocity_tolerance, kInteriorRounds, shift);
      report.interior_iterations += interior.iterations;
      if (interior.improved) std::fill(settled.begin(), settled.end(), 0);
    }
  }
  if (groups == 0) report.converged = true;
  return report;
}

}  // namespace ashlar
