#include "dynamics/simulation.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_loop.hpp"
#include "core/point_grid.hpp"
#include "core/text.hpp"
#include "dynamics/contact_points.hpp"
#include "dynamics/contact_solver.hpp"

namespace ashlar {
namespace {

// Fraction of an overlap (beyond the contact tolerance) that one step's
// position correction removes.
constexpr double kOverlapCorrection = 0.5;
// Contact points from which their geometry each step is shared over the
// threads: below it a wake-up of the helpers costs more than the pass
// (about 0.1 ms per 2,000 points).
constexpr int kParallelPoints = 4000;
// A step whose contact solve stops at max_sweeps with its residual within
// kSplitWithin times the tolerance is taken again in halves (Run::step),
// and so on, at most kStepSplits times over: down to a 64th of the step. A
// shorter step changes the velocities less, and its solve starts nearer
// its answer. Six collapsing arches (8,700 steps of 1 ms, mostly after
// their first fall; tests/tools/convergence_runs.lua arches) leave 23
// steps unconverged unsplit (up to 8e-5 m/s) and none split so (38 steps
// split, 13.1 s against 11.7). Before the interior-point method finished
// stalled solves, splits within 2 tolerances down to a quarter left 72,
// within 1,000 down to a 64th none, and a split that stalled again cost
// its solve twice over: a wall shaken past its load factor (106 blocks at
// 1.5 g, 50 steps, 23 of them unconverged at 1,919 sweeps a step) took
// more than 17 times as long split so. A run therefore splits at most
// kFirstSplits + kSplitsPerStep times its steps so far.
constexpr int kStepSplits = 6;
constexpr double kSplitWithin = 1000.0;
constexpr double kSplitsPerStep = 0.1;
constexpr int kFirstSplits = 8;

[[noreturn]] void fail(const std::string& what, double value, const std::string& allowed) {
  throw InvalidArgument("simulate: " + what + " must be " + allowed + ", got " + shortest_number(value));
}

void check_options(const SimulationOptions& o) {
  if (!(o.duration > 0.0) || !std::isfinite(o.duration)) fail("duration", o.duration, "a time > 0 (s)");
  if (!(o.step > 0.0) || !std::isfinite(o.step)) fail("step", o.step, "a time > 0 (s)");
  if (o.step > o.duration) fail("step", o.step, "at most the duration (" + shortest_number(o.duration) + " s)");
  if (o.duration / o.step > 1e9) fail("step", o.step, "at least duration / 1e9");
  if (!(o.theta >= 0.5 && o.theta <= 1.0)) fail("theta", o.theta, "in [0.5, 1]");
  if (!(o.friction >= 0.0)) fail("friction", o.friction, "a number >= 0 (inf: no sliding)");
  if (!(o.restitution >= 0.0 && o.restitution <= 1.0)) fail("restitution", o.restitution, "in [0, 1]");
  for (int axis = 0; axis < 3; ++axis) {
    if (!std::isfinite(o.gravity[axis])) fail("gravity", o.gravity[axis], "a finite vector (m/s^2)");
    if (!std::isfinite(o.ground_pivot[axis])) fail("ground_pivot", o.ground_pivot[axis], "a finite point (m)");
  }
  if (o.record_every < 0) fail("record_every", o.record_every, "a number of steps >= 0 (0: automatic)");
  if (!(o.search_distance >= 0.0) || !std::isfinite(o.search_distance)) {
    fail("search_distance", o.search_distance, "a distance >= 0 (m; 0: automatic)");
  }
  if (!(o.moved_fraction > 0.0) || !std::isfinite(o.moved_fraction)) fail("moved_fraction", o.moved_fraction, "> 0");
  if (!(o.settle_speed > 0.0) || !std::isfinite(o.settle_speed)) fail("settle_speed", o.settle_speed, "a speed > 0 (m/s)");
  if (o.max_sweeps < 1) fail("max_sweeps", o.max_sweeps, "at least 1");
  if (o.threads < 0) fail("threads", o.threads, "a whole number >= 0 (0: one per core)");
  if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance)) fail("tolerance", o.tolerance, "> 0");
}

Vec3 checked_ground_acceleration(const SimulationOptions& o, double t) {
  if (!o.ground_acceleration) return Vec3::Zero();
  const Vec3 a = o.ground_acceleration(t);
  if (!a.allFinite()) {
    throw InvalidArgument("simulate: ground_acceleration at t = " + shortest_number(t) +
                          " s is not finite: (" + shortest_number(a.x()) + ", " + shortest_number(a.y()) +
                          ", " + shortest_number(a.z()) + ")");
  }
  return a;
}

// The ground's turning as the blocks feel it at one time (simulation.hpp):
// gravity in the ground's axes (m/s^2), and the ground's angular velocity
// (rad/s) and acceleration (rad/s^2) in them.
struct GroundFrame {
  Vec3 gravity, omega, alpha;
};

// The ground's rotation (SimulationOptions::ground_rotation) about step k,
// from t_k = k h to t_k+1: its rotations at t_k-1 .. t_k+2, of which each
// end's frame takes central differences; one new rotation per step.
class GroundRotation {
public:
  explicit GroundRotation(const SimulationOptions& o) : o_(o) {
    for (int j = 0; j < 4; ++j) turns_[j] = rotation_at((j - 1) * o.step);
  }
  // Moves on to step k (> 0, in turn).
  void advance(int k) {
    std::rotate(turns_.begin(), turns_.begin() + 1, turns_.end());
    turns_[3] = rotation_at((k + 2) * o_.step);
  }
  GroundFrame at_start() const { return frame(0); }
  GroundFrame at_end() const { return frame(1); }

private:
  Quat rotation_at(double t) const {
    const Vec3 theta = o_.ground_rotation(t);
    if (!theta.allFinite()) {
      throw InvalidArgument("simulate: ground_rotation at t = " + shortest_number(t) + " s is not finite: (" +
                            shortest_number(theta.x()) + ", " + shortest_number(theta.y()) + ", " +
                            shortest_number(theta.z()) + ")");
    }
    return quaternion_from_rotation_vector(theta);
  }
  GroundFrame frame(int j) const {
    const Quat &before = turns_[j], &now = turns_[j + 1], &after = turns_[j + 2];
    const Vec3 ahead = rotation_vector(now.conjugate() * after) / o_.step;
    const Vec3 behind = rotation_vector(before.conjugate() * now) / o_.step;
    return {now.conjugate() * o_.gravity, 0.5 * (ahead + behind), (ahead - behind) / o_.step};
  }

  const SimulationOptions& o_;
  std::array<Quat, 4> turns_;
};

// What stays fixed about each block through the run.
struct BodyData {
  bool fixed = false;
  double mass = 0.0;              // kg
  Mat3 inertia = Mat3::Zero();    // kg m^2, reference frame, about the centroid
  Mat3 inverse_inertia = Mat3::Zero();
  double radius = 0.0;            // m, farthest vertex from the centroid
  double size = 0.0;              // m, bounding-box diagonal
  Vec3 force = Vec3::Zero();      // N, point loads summed
  Vec3 load_moment = Vec3::Zero();  // N m about the reference centroid, reference frame
  std::vector<std::pair<Vec3, Vec3>> loads;  // (arm from the reference centroid, force)
};

class Run {
public:
  Run(const Structure& structure, const SimulationOptions& options)
      : s_(structure), o_(options), n_(structure.size()) {}

  SimulationResult go();

private:
  void set_up();
  void search(const std::vector<int>& moved);
  std::vector<int> neighbourhood(const std::vector<int>& moved) const;
  void free_velocities(const Vec3& ground);  // and the ground's turning, rotation_
  // warm_scale: the points' last impulses times it start the solve.
  void contact_rows(std::vector<int>& which, std::vector<ContactRow>& rows, const std::vector<Vec3>& linear,
                    const std::vector<Vec3>& angular, double warm_scale);
  // One step of length h (s) from the present state, the ground's
  // acceleration going from ground_start to ground_end over it, ending at
  // end_time (s). False, with nothing changed, when may_split and its
  // contact solve stalled within kSplitWithin times the tolerance: the
  // caller takes it in halves. Otherwise the step is taken, and converged is
  // cleared if its solve did not converge.
  bool advance(double h, const Vec3& ground_start, const Vec3& ground_end, double end_time, bool may_split,
               bool& converged);
  // A step of length h, split in halves up to `splits` times over where
  // its contact solve stalls within kSplitWithin tolerances (advance),
  // while the run's splits are within their budget (kSplitsPerStep).
  void step(double h, const Vec3& ground_start, const Vec3& ground_end, double end_time, int splits,
            bool& converged);
  void integrate(const std::vector<Vec3>& linear0, const std::vector<Vec3>& angular0);
  void correct_overlaps(const std::vector<int>& active);
  void record(double t);
  // A solver row for contact c where it stands (geometry g): bodies, arms,
  // frame; no friction, target or impulse yet.
  ContactRow row_at(const ContactPoint& c, const ContactGeometry& g) const {
    ContactRow row;
    row.a = c.a;
    row.b = c.b;
    row.arm_a = g.point - poses_[c.a].position;
    row.arm_b = g.point - poses_[c.b].position;
    row.frame = contact_frame(g.normal);
    return row;
  }
  Vec3 point_velocity(int body, const Vec3& point, const std::vector<Vec3>& linear,
                      const std::vector<Vec3>& angular) const {
    return linear[body] + angular[body].cross(point - poses_[body].position);
  }

  const Structure& s_;
  const SimulationOptions& o_;
  const int n_;
  double h_ = 0.0, tolerance_ = 0.0, distance_ = 0.0;
  std::vector<BodyData> data_;
  std::vector<bool> fixed_;
  std::vector<RigidPose> poses_, start_, searched_;
  BodyVelocities bodies_;
  std::vector<ContactPoint> contacts_;
  ContactSolverSettings solver_;
  // The steps' solves and the overlap corrections' (each keeps its
  // factorisation from step to step).
  ContactSolver contact_solver_{o_.threads}, overlap_solver_{o_.threads};
  // The contact points' geometry each step, each point alone, shared over
  // the same threads from kParallelPoints points; the points' rows where
  // they stand (a = -1 where a point is not active).
  ParallelLoop geometry_loop_{o_.threads > 0 ? std::min(o_.threads, ParallelLoop::kMaxThreads) : 0, kParallelPoints};
  std::vector<ContactRow> candidates_;
  std::vector<ContactGeometry> geometry_;  // of the active points, after the step
  std::vector<ContactRow> rows_;           // the step's rows (kept for their memory)
  std::vector<int> active_;                // the step's rows' contact points (indices into contacts_)
  std::optional<GroundRotation> rotation_;  // when the ground turns
  SimulationResult result_;
};

void Run::set_up() {
  data_.resize(n_);
  fixed_.resize(n_);
  poses_.resize(n_);
  bodies_.linear.assign(n_, Vec3::Zero());
  bodies_.angular.assign(n_, Vec3::Zero());
  bodies_.inverse_mass.assign(n_, 0.0);
  bodies_.inverse_inertia.assign(n_, Mat3::Zero());
  double smallest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_; ++i) {
    const Block& block = s_.block(i);
    BodyData& d = data_[i];
    d.fixed = fixed_[i] = s_.is_support(i);
    d.size = block.bounds().diagonal();
    for (const Vec3& p : block.vertices()) d.radius = std::max(d.radius, (p - block.centroid()).norm());
    poses_[i].position = block.centroid();
    if (d.fixed) continue;
    smallest = std::min(smallest, d.size);
    d.mass = block.mass();
    if (!(d.mass > 0.0)) {
      throw InvalidArgument("simulate: " + s_.label(i) + " has no mass (density " +
                            shortest_number(block.density()) + "); a free block needs a density > 0");
    }
    d.inertia = inertia_tensor(block);
    d.inverse_inertia = d.inertia.inverse();
    bodies_.inverse_mass[i] = 1.0 / d.mass;
    bodies_.inverse_inertia[i] = d.inverse_inertia;
  }
  for (const PointLoad& load : s_.loads()) {
    data_[load.block].loads.emplace_back(load.at - s_.block(load.block).centroid(), load.force);
  }
  start_ = searched_ = poses_;
  h_ = o_.step;
  tolerance_ = s_.contact_tolerance(o_.contact);
  distance_ = o_.search_distance > 0.0 ? o_.search_distance : 0.02 * smallest;
  distance_ = std::max(distance_, 2.0 * tolerance_);
  solver_.max_sweeps = o_.max_sweeps;
  solver_.velocity_tolerance = o_.tolerance * kGravity * h_;
  result_.displacement.assign(n_, 0.0);
}

// The moved blocks and every block that may come within the search
// distance of one: centroids closer than the two radii plus the distance.
// Centroids go in a point grid sized for the blocks; the few much larger
// ones (a ground slab) are checked against each moved block directly.
std::vector<int> Run::neighbourhood(const std::vector<int>& moved) const {
  std::vector<double> radii;
  for (const BodyData& d : data_) radii.push_back(d.radius);
  std::nth_element(radii.begin(), radii.begin() + n_ / 2, radii.end());
  const double large = 4.0 * radii[n_ / 2];
  double largest_small = 0.0;
  std::vector<int> big;
  for (int i = 0; i < n_; ++i) {
    if (data_[i].radius > large) big.push_back(i);
    else largest_small = std::max(largest_small, data_[i].radius);
  }
  PointGrid grid(Vec3::Zero(), 2.0 * largest_small + distance_);
  for (int i = 0; i < n_; ++i) {
    if (data_[i].radius <= large) grid.insert(poses_[i].position, i);
  }
  std::vector<char> in(n_, 0);
  const auto near = [&](int i, int j) {
    if ((poses_[i].position - poses_[j].position).norm() <= data_[i].radius + data_[j].radius + distance_) in[j] = 1;
  };
  for (int i : moved) {
    in[i] = 1;
    grid.for_each_near(poses_[i].position, data_[i].radius + largest_small + distance_, [&](int j) { near(i, j); });
    for (int j : big) near(i, j);
  }
  std::vector<int> which;
  for (int i = 0; i < n_; ++i) {
    if (in[i]) which.push_back(i);
  }
  return which;
}

void Run::search(const std::vector<int>& moved) {
  const std::vector<int> which = moved.size() == static_cast<size_t>(n_) ? moved : neighbourhood(moved);
  std::vector<char> in(n_, 0);
  for (int i : which) in[i] = 1;
  // Blocks where they stand: the built block itself until it moves.
  std::vector<std::unique_ptr<Block>> moved_blocks;
  std::vector<const Block*> posed(n_, nullptr);
  for (int i : which) {
    const bool at_start = poses_[i].position == start_[i].position && poses_[i].rotation.coeffs() == start_[i].rotation.coeffs();
    if (at_start) {
      posed[i] = &s_.block(i);
    } else {
      moved_blocks.push_back(std::make_unique<Block>(posed_block(s_.block(i), poses_[i])));
      posed[i] = moved_blocks.back().get();
    }
  }
  std::vector<ContactPoint> found = find_contact_points(posed, poses_, fixed_, which, distance_, o_.contact.angle);
  // Warm starts: the impulse of the old point of the same pair and face
  // nearest each new one, within half the search distance.
  std::map<std::tuple<int, int, int>, std::vector<const ContactPoint*>> old;
  for (const ContactPoint& c : contacts_) {
    if (in[c.a] && in[c.b]) old[{c.a, c.b, c.face}].push_back(&c);
  }
  for (ContactPoint& c : found) {
    const auto same = old.find({c.a, c.b, c.face});
    if (same == old.end()) continue;
    double nearest = 0.5 * distance_;
    for (const ContactPoint* previous : same->second) {
      const double d = (previous->point - c.point).norm();
      if (d <= nearest) {
        nearest = d;
        c.impulse = previous->impulse;
      }
    }
  }
  contacts_.erase(std::remove_if(contacts_.begin(), contacts_.end(),
                                 [&](const ContactPoint& c) { return in[c.a] && in[c.b]; }),
                  contacts_.end());
  contacts_.insert(contacts_.end(), found.begin(), found.end());
  std::stable_sort(contacts_.begin(), contacts_.end(), [](const ContactPoint& x, const ContactPoint& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  for (int i : moved) searched_[i] = poses_[i];
  ++result_.searches;
}

void Run::free_velocities(const Vec3& ground) {
  // The turning ground's frames at the step's two ends and their weights.
  const double theta = o_.theta;
  const std::array<std::pair<double, GroundFrame>, 2> turning =
      rotation_ ? std::array{std::pair{1.0 - theta, rotation_->at_start()}, std::pair{theta, rotation_->at_end()}}
                : std::array<std::pair<double, GroundFrame>, 2>{};
  const Vec3 gravity =
      rotation_ ? Vec3(turning[0].first * turning[0].second.gravity + turning[1].first * turning[1].second.gravity)
                : o_.gravity;
  for (int i = 0; i < n_; ++i) {
    if (fixed_[i]) continue;
    const BodyData& d = data_[i];
    const Mat3 r = poses_[i].rotation.toRotationMatrix();
    const Mat3 inverse_inertia = r * d.inverse_inertia * r.transpose();
    bodies_.inverse_inertia[i] = inverse_inertia;
    Vec3 force = d.mass * (gravity - ground);
    Vec3 moment = Vec3::Zero();
    for (const auto& [arm, load] : d.loads) {
      force += load;
      moment += (r * arm).cross(load);
    }
    const Vec3& w = bodies_.angular[i];
    const Mat3 inertia = r * d.inertia * r.transpose();
    moment -= w.cross(inertia * w);  // gyroscopic
    if (rotation_) {
      const Vec3 arm = poses_[i].position - o_.ground_pivot;
      const Vec3& v = bodies_.linear[i];
      for (const auto& [weight, f] : turning) {
        force -= weight * d.mass * (f.alpha.cross(arm) + f.omega.cross(f.omega.cross(arm)) + 2.0 * f.omega.cross(v));
        moment -= weight * (inertia * f.alpha + f.omega.cross(inertia * f.omega) + f.omega.cross(inertia * w) +
                            w.cross(inertia * f.omega) - inertia * w.cross(f.omega));
      }
    }
    bodies_.linear[i] += h_ * force / d.mass;
    bodies_.angular[i] += h_ * inverse_inertia * moment;
  }
}

// Into rows: the rows of the contact points whose gap, half a step ahead at the velocities
// of the step's start, is within the contact tolerance, from the highest
// down; `which` gets their indices into contacts_.
void Run::contact_rows(std::vector<int>& which, std::vector<ContactRow>& rows, const std::vector<Vec3>& linear,
                       const std::vector<Vec3>& angular, double warm_scale) {
  candidates_.resize(contacts_.size());
  geometry_loop_.run(static_cast<int>(contacts_.size()), [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      const ContactPoint& c = contacts_[k];
      const ContactGeometry g = contact_geometry(c, poses_);
      const double approach =
          g.normal.dot(point_velocity(c.b, g.point, linear, angular) - point_velocity(c.a, g.point, linear, angular));
      ContactRow& row = candidates_[k];
      if (g.gap + 0.5 * h_ * approach > tolerance_) {
        row.a = -1;
        continue;
      }
      row = row_at(c, g);
      row.friction = o_.friction;
      row.target_normal = o_.restitution * std::max(0.0, -approach);
      row.impulse = warm_scale * (row.frame * c.impulse);
    }
  });
  which.clear();
  for (size_t k = 0; k < contacts_.size(); ++k) {
    if (candidates_[k].a >= 0) which.push_back(static_cast<int>(k));
  }
  // Each pair's points together (the solver's groups: contacts_ is sorted
  // by pair), the pairs from the top down (against gravity, by their
  // highest point): a sweep then carries each block's weight down the load
  // path to the supports.
  struct Group {
    size_t begin, end;
    double height;
  };
  std::vector<Group> groups;
  for (size_t r = 0; r < which.size(); ++r) {
    const ContactRow& row = candidates_[which[r]];
    const double height = -o_.gravity.dot(row.arm_a + poses_[row.a].position);
    if (groups.empty() || row.a != candidates_[which[groups.back().begin]].a ||
        row.b != candidates_[which[groups.back().begin]].b) {
      groups.push_back({r, r + 1, height});
    } else {
      groups.back().end = r + 1;
      groups.back().height = std::max(groups.back().height, height);
    }
  }
  std::stable_sort(groups.begin(), groups.end(), [](const Group& x, const Group& y) { return x.height > y.height; });
  std::vector<int> sorted_which;
  sorted_which.reserve(which.size());
  rows.clear();
  for (const Group& group : groups) {
    for (size_t r = group.begin; r < group.end; ++r) {
      rows.push_back(candidates_[which[r]]);
      sorted_which.push_back(which[r]);
    }
  }
  which.swap(sorted_which);
}

void Run::integrate(const std::vector<Vec3>& linear0, const std::vector<Vec3>& angular0) {
  const double theta = o_.theta;
  for (int i = 0; i < n_; ++i) {
    if (fixed_[i]) continue;
    poses_[i].position += h_ * ((1.0 - theta) * linear0[i] + theta * bodies_.linear[i]);
    const Vec3 turn = h_ * ((1.0 - theta) * angular0[i] + theta * bodies_.angular[i]);
    poses_[i].rotation = (quaternion_from_rotation_vector(turn) * poses_[i].rotation).normalized();
  }
}

// Moves blocks apart where active contacts overlap by more than the
// tolerance: a frictionless solve for pseudo-velocities that would close
// kOverlapCorrection of each overlap in one step, applied to positions
// only.
void Run::correct_overlaps(const std::vector<int>& active) {
  geometry_.resize(active.size());
  geometry_loop_.run(static_cast<int>(active.size()), [&](int begin, int end, int) {
    for (int r = begin; r < end; ++r) geometry_[r] = contact_geometry(contacts_[active[r]], poses_);
  });
  std::vector<ContactRow> rows;
  for (size_t r = 0; r < active.size(); ++r) {
    const ContactPoint& c = contacts_[active[r]];
    const ContactGeometry& g = geometry_[r];
    if (g.gap >= -tolerance_) continue;
    ContactRow row = row_at(c, g);
    row.target_normal = kOverlapCorrection * (-g.gap - tolerance_) / h_;
    rows.push_back(row);
  }
  if (rows.empty()) return;
  BodyVelocities pseudo{std::vector<Vec3>(n_, Vec3::Zero()), std::vector<Vec3>(n_, Vec3::Zero()),
                        bodies_.inverse_mass, bodies_.inverse_inertia};
  overlap_solver_.solve(rows, pseudo, solver_);
  for (int i = 0; i < n_; ++i) {
    if (fixed_[i]) continue;
    poses_[i].position += h_ * pseudo.linear[i];
    poses_[i].rotation = (quaternion_from_rotation_vector(h_ * pseudo.angular[i]) * poses_[i].rotation).normalized();
  }
}

bool Run::advance(double h, const Vec3& ground_start, const Vec3& ground_end, double end_time, bool may_split,
                  bool& converged) {
  // The contact points' impulses are the last step's, of length h_: they
  // scale with the step.
  const double last_h = h_, warm_scale = h / last_h;
  h_ = h;
  const std::vector<Vec3> linear0 = bodies_.linear, angular0 = bodies_.angular;
  free_velocities((1.0 - o_.theta) * ground_start + o_.theta * ground_end);
  contact_rows(active_, rows_, linear0, angular0, warm_scale);
  const ContactSolverReport report = contact_solver_.solve(rows_, bodies_, solver_);
  result_.sweeps += report.sweeps;
  result_.global_steps += report.global_steps;
  result_.factorizations += report.factorizations;
  if (!report.converged && may_split && report.residual <= kSplitWithin * solver_.velocity_tolerance) {
    // Taken again in halves, from where it began.
    h_ = last_h;
    bodies_.linear = linear0;
    bodies_.angular = angular0;
    return false;
  }
  converged = converged && report.converged;
  if (report.worst_row >= 0 && report.residual > result_.max_residual) {
    result_.max_residual = report.residual;
    result_.max_residual_time = end_time;
    result_.max_residual_blocks = {rows_[report.worst_row].a, rows_[report.worst_row].b};
  }
  result_.max_active_contacts = std::max(result_.max_active_contacts, static_cast<int>(rows_.size()));
  for (ContactPoint& c : contacts_) c.impulse.setZero();
  for (size_t r = 0; r < rows_.size(); ++r) contacts_[active_[r]].impulse = rows_[r].frame.transpose() * rows_[r].impulse;
  integrate(linear0, angular0);
  correct_overlaps(active_);
  return true;
}

void Run::step(double h, const Vec3& ground_start, const Vec3& ground_end, double end_time, int splits,
               bool& converged) {
  const bool within_budget = result_.split_steps < kFirstSplits + kSplitsPerStep * result_.steps;
  if (advance(h, ground_start, ground_end, end_time, splits > 0 && within_budget, converged)) return;
  ++result_.split_steps;
  const Vec3 ground_middle = 0.5 * (ground_start + ground_end);  // a_g linear over the step
  step(0.5 * h, ground_start, ground_middle, end_time - 0.5 * h, splits - 1, converged);
  step(0.5 * h, ground_middle, ground_end, end_time, splits - 1, converged);
}

void Run::record(double t) {
  result_.times.push_back(t);
  result_.poses.push_back(poses_);
}

SimulationResult Run::go() {
  const Clock::time_point started = Clock::now();
  set_up();
  std::vector<int> everything(n_);
  for (int i = 0; i < n_; ++i) everything[i] = i;
  search(everything);
  const int record_every = o_.record_every > 0 ? o_.record_every : std::max(1, static_cast<int>(std::lround(0.01 / h_)));
  const int steps = static_cast<int>(std::ceil(o_.duration / h_ - 1e-9));
  record(0.0);
  Vec3 ground_before = checked_ground_acceleration(o_, 0.0);
  if (o_.ground_rotation) rotation_.emplace(o_);
  for (int k = 0; k < steps; ++k) {
    if (stop_requested()) {
      result_.status = SimulationStatus::interrupted;
      break;
    }
    const double t = (k + 1) * o_.step;
    const Vec3 ground_after = checked_ground_acceleration(o_, t);
    if (rotation_ && k > 0) rotation_->advance(k);
    bool converged = true;
    step(o_.step, ground_before, ground_after, t, rotation_ ? 0 : kStepSplits, converged);
    if (!converged) ++result_.unconverged_steps;
    ground_before = ground_after;
    result_.steps = k + 1;
    result_.time = t;

    std::vector<int> moved;
    for (int i = 0; i < n_; ++i) {
      if (fixed_[i]) continue;
      const Block& block = s_.block(i);
      result_.displacement[i] = std::max(result_.displacement[i], vertex_distance(block, poses_[i], start_[i]));
      if (vertex_distance(block, poses_[i], searched_[i]) > 0.5 * distance_) moved.push_back(i);
    }
    if (!moved.empty()) search(moved);
    if ((k + 1) % record_every == 0 || k + 1 == steps) record(t);
    if (o_.progress) o_.progress(t);
  }
  if (result_.times.back() != result_.time) record(result_.time);

  for (int i = 0; i < n_; ++i) {
    if (result_.displacement[i] > result_.max_displacement) {
      result_.max_displacement = result_.displacement[i];
      result_.max_displacement_block = i;
    }
  }
  if (result_.status == SimulationStatus::completed) {
    result_.settled = true;
    for (int i = 0; i < n_; ++i) {
      if (fixed_[i]) continue;
      result_.moved = result_.moved || result_.displacement[i] > o_.moved_fraction * data_[i].size;
      const double speed = bodies_.linear[i].norm() + bodies_.angular[i].norm() * data_[i].radius;
      result_.settled = result_.settled && speed < o_.settle_speed;
    }
  }
  result_.seconds = seconds_since(started);
  return std::move(result_);
}

}  // namespace

SimulationResult simulate(const Structure& structure, const SimulationOptions& options) {
  check_options(options);
  structure.require_free_block("simulate");
  structure.require_detected_interfaces("simulate");
  if (!structure.cables().empty()) {
    throw InvalidArgument("simulate: cables are not simulated, and this structure has " +
                          std::to_string(structure.cables().size()) +
                          " (ashlar.analyze takes them into account)");
  }
  structure.require_no_overlaps(options.contact, "simulate");
  return Run(structure, options).go();
}

std::vector<RigidPose> poses_at(const SimulationResult& result, double t) {
  const std::vector<double>& times = result.times;
  const auto after = std::upper_bound(times.begin(), times.end(), t);
  if (after == times.begin()) return result.poses.front();
  if (after == times.end()) return result.poses.back();
  const size_t k = static_cast<size_t>(after - times.begin());
  const double w = (t - times[k - 1]) / (times[k] - times[k - 1]);
  std::vector<RigidPose> poses = result.poses[k - 1];
  for (size_t i = 0; i < poses.size(); ++i) {
    const RigidPose& next = result.poses[k][i];
    poses[i].position = (1.0 - w) * poses[i].position + w * next.position;
    poses[i].rotation = poses[i].rotation.slerp(w, next.rotation);
  }
  return poses;
}

Structure posed_structure(const Structure& structure, const std::vector<RigidPose>& poses) {
  Structure out;
  for (int i = 0; i < structure.size(); ++i) {
    out.add(std::make_shared<const Block>(posed_block(structure.block(i), poses.at(i))), structure.is_support(i),
            structure.name(i));
  }
  for (PointLoad load : structure.loads()) {
    const RigidPose& pose = poses.at(load.block);
    load.at = pose.apply(load.at, structure.block(load.block).centroid());
    out.add_load(load);
  }
  return out;
}

}  // namespace ashlar
