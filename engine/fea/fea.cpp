#include "fea/fea.hpp"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <functional>
#include <map>
#include <set>

#include "core/sparse_cholesky.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "fea/contact_program.hpp"

namespace ashlar {

const char* fea_status_name(FeaStatus status) {
  return kFeaStatusNames.name(status);
}

namespace {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using Triplet = Eigen::Triplet<double, int>;

void check_settings(const Structure& structure, const FeaSettings& s) {
  const auto fail = [](const std::string& message) { throw InvalidArgument(message); };
  if (!(std::isfinite(s.material.young) && s.material.young > 0))
    fail("young: expected a finite number > 0 (Pa), got " + std::to_string(s.material.young));
  if (!(s.material.poisson > -1 && s.material.poisson < 0.5))
    fail("poisson: expected a number in (-1, 0.5), got " + std::to_string(s.material.poisson));
  if (s.max_relax_iterations < 0 || s.max_relax_iterations > 100000)
    fail("max_relax_iterations: expected a whole number from 0 to 100000");
  if (!(std::isfinite(s.tension_tolerance) && s.tension_tolerance >= 0))
    fail("tension_tolerance: expected a finite number >= 0");
  if (!(std::isfinite(s.max_displacement) && s.max_displacement > 0))
    fail("max_displacement: expected a finite number > 0");
  if (!structure.cables().empty())
    fail("the FEA does not model cables, and the structure has " +
         std::to_string(structure.cables().size()) + "; analyse it with ashlar.analyze");
}

// True when q (in the interface plane's u, v frame) lies in the polygon or
// within tol of its boundary, and not inside a hole by more than tol.
double distance_to_loop(const Loop2& loop, const Vec2& q) {
  double best = std::numeric_limits<double>::infinity();
  for (size_t e = 0; e < loop.size(); ++e) {
    const Vec2 p = loop[e], d = loop[(e + 1) % loop.size()] - p;
    const double t = d.squaredNorm() > 0 ? std::clamp((q - p).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (p + t * d - q).norm());
  }
  return best;
}

bool inside_loop(const Loop2& loop, const Vec2& q) {
  bool inside = false;
  for (size_t e = 0, f = loop.size() - 1; e < loop.size(); f = e++) {
    const Vec2& p = loop[e];
    const Vec2& r = loop[f];
    if ((p.y() > q.y()) != (r.y() > q.y()) &&
        q.x() < (r.x() - p.x()) * (q.y() - p.y()) / (r.y() - p.y()) + p.x())
      inside = !inside;
  }
  return inside;
}

struct PlanarRegion {
  Vec3 origin, normal, u, v;
  Loop2 outer;
  std::vector<Loop2> holes;

  explicit PlanarRegion(const Interface& face) : origin(face.center), normal(face.normal), u(face.u), v(face.v) {
    outer = project(face.vertices);
    for (const auto& hole : face.holes) holes.push_back(project(hole));
  }
  Loop2 project(const std::vector<Vec3>& loop) const {
    Loop2 out;
    for (const Vec3& p : loop) out.emplace_back((p - origin).dot(u), (p - origin).dot(v));
    return out;
  }
  bool contains(const Vec3& p, double tol) const {
    if (std::abs((p - origin).dot(normal)) > tol) return false;
    const Vec2 q((p - origin).dot(u), (p - origin).dot(v));
    if (!inside_loop(outer, q) && distance_to_loop(outer, q) > tol) return false;
    for (const Loop2& hole : holes)
      if (inside_loop(hole, q) && distance_to_loop(hole, q) > tol) return false;
    return true;
  }
};

bool single_node(const NodeWeights& w) { return w.nodes.size() == 1 && std::abs(w.weights[0] - 1) < 1e-9; }

// Contact ties of every interface. A free block's nodes on the contact
// polygon are tied to the other block (or the ground); the other block's
// nodes that do not coincide with one of those are tied back, so matching
// meshes get one tie per node pair and mismatched ones are tied both ways.
std::vector<FeaContact> contact_ties(const Structure& structure, const FeaMesh& mesh,
                                     const std::vector<Interface>& interfaces, double tol) {
  std::vector<FeaContact> ties;
  std::vector<std::vector<int>> surface(structure.size());
  for (int b = 0; b < structure.size(); ++b)
    if (mesh.meshed(b)) surface[b] = mesh.surface_nodes(b);
  for (int k = 0; k < static_cast<int>(interfaces.size()); ++k) {
    const Interface& face = interfaces[k];
    const PlanarRegion region(face);
    std::vector<int> covered;
    const auto tie_side = [&](int own, int other) {
      if (!mesh.meshed(own)) return;
      for (int node : surface[own]) {
        const Vec3& p = mesh.nodes()[node];
        if (!region.contains(p, tol)) continue;
        if (std::find(covered.begin(), covered.end(), node) != covered.end()) continue;
        FeaContact tie;
        tie.interface = k;
        tie.node = node;
        tie.block = own;
        if (mesh.meshed(other)) {
          tie.target = mesh.locate(other, p);
          if (single_node(tie.target)) covered.push_back(tie.target.nodes[0]);
        }
        ties.push_back(std::move(tie));
      }
    };
    tie_side(face.a, face.b);
    tie_side(face.b, face.a);
  }
  return ties;
}

// Rows 3t + d of A: u_node,d - sum_m w_m u_m,d.
template <class Visit>
void for_each_tie_entry(const FeaContact& tie, Visit&& visit) {
  visit(tie.node, 1.0);
  for (size_t m = 0; m < tie.target.nodes.size(); ++m) visit(tie.target.nodes[m], -tie.target.weights[m]);
}

Vec3 tie_gap(const FeaContact& tie, const Eigen::VectorXd& u) {
  Vec3 gap = Vec3::Zero();
  for_each_tie_entry(tie, [&](int node, double w) { gap += w * u.segment<3>(3 * node); });
  return gap;
}

// Stiffness and loads of the free blocks.
struct Assembly {
  std::vector<Triplet> stiffness;  // upper triangle
  Eigen::VectorXd loads;
  double total_weight = 0;
  double mean_diagonal = 0;
};

Assembly assemble(const Structure& structure, const FeaMesh& mesh, const Elasticity& material) {
  Assembly out;
  const int dofs = 3 * static_cast<int>(mesh.nodes().size());
  out.loads = Eigen::VectorXd::Zero(dofs);
  out.stiffness.reserve(mesh.elements().size() * 300);
  double diagonal = 0;
  for (int e = 0; e < static_cast<int>(mesh.elements().size()); ++e) {
    const HexNodes nodes = mesh.element_nodes(e);
    const std::array<int, 8>& index = mesh.elements()[e];
    const HexStiffness k = hex_stiffness(nodes, material);
    for (int a = 0; a < 24; ++a)
      for (int b = 0; b < 24; ++b) {
        const int row = 3 * index[a / 3] + a % 3, col = 3 * index[b / 3] + b % 3;
        if (row <= col) out.stiffness.emplace_back(row, col, k(a, b));
      }
    diagonal += k.diagonal().sum();
    const double density = structure.block(mesh.element_block(e)).density();
    const HexVector f = hex_body_load(nodes, Vec3(0, 0, -kGravity * density));
    for (int a = 0; a < 8; ++a) out.loads.segment<3>(3 * index[a]) += f.segment<3>(3 * a);
  }
  for (int b = 0; b < structure.size(); ++b)
    if (mesh.meshed(b)) out.total_weight += structure.block(b).mass() * kGravity;
  out.mean_diagonal = dofs > 0 ? diagonal / dofs : 0;
  const std::vector<PointLoad>& loads = structure.loads();
  for (size_t l = 0; l < loads.size(); ++l) {
    const PointLoad& load = loads[l];
    if (!mesh.meshed(load.block)) continue;  // the ground takes it
    const Vec3 xi = hex_parametric(mesh.corners(load.block), load.at);
    if (xi.cwiseAbs().maxCoeff() > 1 + 1e-6)
      throw InvalidArgument("load " + std::to_string(l + 1) + ": its point lies outside block " +
                            std::to_string(load.block + 1) + ", and the FEA applies a load where it acts");
    const NodeWeights w = mesh.locate(load.block, load.at);
    for (size_t m = 0; m < w.nodes.size(); ++m) out.loads.segment<3>(3 * w.nodes[m]) += w.weights[m] * load.force;
  }
  return out;
}

// Unilateral contact: an open node overlaps when its opening is below
// -kOverlapTolerance x the largest displacement of the first (all-tied)
// solve. Like tension_tolerance for closed nodes, it keeps round-off on a
// node that touches without force from opening and closing it forever.
constexpr double kOverlapTolerance = 1e-6;

// Unilateral contact: active-set steps before the interior-point program
// takes over. The model library needs 0-6 where the iteration converges;
// where it does not, it cycles or creeps one interface at a time.
constexpr int kActiveSetSteps = 10;

// How a contact node is held in one solve.
enum class Hold : unsigned char {
  All,         // tied in all three directions: closed
  Tangential,  // the normal free: open (unilateral contact)
  None,        // free: released (relaxation)
};

// The part of a tie's relative displacement (or force) that the hold ties.
Vec3 held_part(Hold hold, const Vec3& normal, const Vec3& v) {
  switch (hold) {
    case Hold::All: return v;
    case Hold::Tangential: return v - normal * normal.dot(v);
    case Hold::None: break;
  }
  return Vec3::Zero();
}

// K + rho A^T A over one fixed pattern (every tie's 3 x 3 blocks, whatever
// its hold), so CHOLMOD analyses the ordering once and each change of holds
// only refactorises from K's values plus the held ties' terms, placed once.
class TiedSystem {
public:
  TiedSystem(const Assembly& assembly, const std::vector<FeaContact>& ties, const std::vector<Vec3>& normals,
             int dofs)
      : ties_(ties), normals_(normals) {
    // A stiff penalty makes each multiplier update contract the constraint
    // error ~1/ratio; 1e4 keeps K + rho A^T A well inside double precision.
    const double mean_diagonal = std::max(assembly.mean_diagonal, 1e-300);
    rho_ = 1e4 * mean_diagonal;
    // A spring of 1e-10 x the mean stiffness from every unknown to the
    // ground keeps the matrix positive definite while the contact state
    // leaves a block free, so the active-set iteration can pass through
    // such states. solve_tied moves the springs' force to the right-hand
    // side, so in an equilibrium they carry nothing; in a mechanism the
    // displacements grow by ~1e10 x elastic ones each step, far past
    // max_displacement.
    ground_spring_ = 1e-10 * mean_diagonal;
    std::vector<Triplet> entries = assembly.stiffness;
    for (int d = 0; d < dofs; ++d) entries.emplace_back(d, d, 0.0);
    for_each_tie_term([&](size_t, int row, int col, int, int, double) { entries.emplace_back(row, col, 0.0); });
    SparseMatrix m(dofs, dofs);
    m.setFromTriplets(entries.begin(), entries.end());
    m.makeCompressed();
    stiffness_values_.assign(m.valuePtr(), m.valuePtr() + m.nonZeros());
    const auto position = [&](int row, int col) {
      const int* first = m.innerIndexPtr() + m.outerIndexPtr()[col];
      const int* last = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
      return static_cast<int>(std::lower_bound(first, last, row) - m.innerIndexPtr());
    };
    for (int d = 0; d < dofs; ++d) {
      const int diagonal = position(d, d);
      stiffness_values_[diagonal] += ground_spring_;
    }
    for_each_tie_term([&](size_t t, int row, int col, int d1, int d2, double weight) {
      tie_terms_.push_back({t, position(row, col), static_cast<unsigned char>(d1), static_cast<unsigned char>(d2), weight});
    });
    std::vector<int> starts(m.outerIndexPtr(), m.outerIndexPtr() + dofs + 1);
    std::vector<int> rows(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
    SparseCholeskyOptions by_nodes;
    by_nodes.block_rows = 3;  // a node's displacements: the elements' and ties' entries come in 3 x 3 blocks
    cholesky_ = std::make_unique<SparseCholesky>(dofs, std::move(starts), std::move(rows), by_nodes);
  }

  double rho() const { return rho_; }
  double ground_spring() const { return ground_spring_; }
  double factor_nonzeros() const { return cholesky_->factor_nonzeros(); }

  bool factorize(const std::vector<Hold>& holds) {
    double* values = cholesky_->values();
    std::copy(stiffness_values_.begin(), stiffness_values_.end(), values);
    for (const TieTerm& term : tie_terms_) {
      // rho w_p w_q P with P = I (All) or I - n n^T (Tangential).
      const Hold hold = holds[term.tie];
      if (hold == Hold::None) continue;
      double entry = term.d1 == term.d2 ? 1.0 : 0.0;
      if (hold == Hold::Tangential) entry -= normals_[term.tie][term.d1] * normals_[term.tie][term.d2];
      values[term.position] += rho_ * term.weight * entry;
    }
    return cholesky_->factorize();
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const { return cholesky_->solve(rhs); }

private:
  struct TieTerm {
    size_t tie;
    int position;              // into the pattern's values
    unsigned char d1, d2;      // directions of its row and column
    double weight;             // w_p w_q of A^T A, without rho
  };

  // Upper-triangle entries (row <= col) of each tie's 3 x 3 blocks of A_t^T A_t.
  template <class Visit>
  void for_each_tie_term(Visit&& visit) const {
    for (size_t t = 0; t < ties_.size(); ++t)
      for_each_tie_entry(ties_[t], [&](int p, double wp) {
        for_each_tie_entry(ties_[t], [&](int q, double wq) {
          if (p > q) return;
          for (int d1 = 0; d1 < 3; ++d1)
            for (int d2 = p == q ? d1 : 0; d2 < 3; ++d2) visit(t, 3 * p + d1, 3 * q + d2, d1, d2, wp * wq);
        });
      });
  }

  const std::vector<FeaContact>& ties_;
  const std::vector<Vec3>& normals_;
  double rho_ = 0, ground_spring_ = 0;
  std::vector<double> stiffness_values_;
  std::vector<TieTerm> tie_terms_;
  std::unique_ptr<SparseCholesky> cholesky_;
};

struct TiedSolution {
  Eigen::VectorXd displacements;
  int steps = 0;
  double constraint_error = 0;
  bool factorized = false;
  bool interrupted = false;
};

// Method of multipliers on the one factorisation: u solves
// (K + rho A^T A) u = f - A^T lambda, then lambda += rho A u (the held
// part), until A u = 0 to round-off; the limit is the KKT solution of the
// equality-tied problem. `multipliers` (per tie) start from the previous
// contact state's, which a small change of holds barely moves.
TiedSolution solve_tied(TiedSystem& system, const std::vector<FeaContact>& ties, const std::vector<Vec3>& normals,
                        const std::vector<Hold>& holds, const Eigen::VectorXd& loads, std::vector<Vec3>& multipliers) {
  TiedSolution out;
  for (size_t t = 0; t < ties.size(); ++t) multipliers[t] = held_part(holds[t], normals[t], multipliers[t]);
  if (stop_requested()) {
    out.interrupted = true;
    return out;
  }
  out.factorized = system.factorize(holds);
  if (!out.factorized) return out;
  for (out.steps = 1; out.steps <= 100; ++out.steps) {
    if (stop_requested()) {
      out.interrupted = true;
      return out;
    }
    // The ground springs' force at the last iterate goes back on the right:
    // at the fixed point they carry nothing.
    Eigen::VectorXd rhs = loads;
    if (out.displacements.size() == rhs.size()) rhs += system.ground_spring() * out.displacements;
    for (size_t t = 0; t < ties.size(); ++t)
      if (holds[t] != Hold::None)
        for_each_tie_entry(ties[t], [&](int node, double w) { rhs.segment<3>(3 * node) -= w * multipliers[t]; });
    out.displacements = system.solve(rhs);
    const double scale = std::max(out.displacements.cwiseAbs().maxCoeff(), 1e-300);
    out.constraint_error = 0;
    for (size_t t = 0; t < ties.size(); ++t) {
      if (holds[t] == Hold::None) continue;
      const Vec3 gap = held_part(holds[t], normals[t], tie_gap(ties[t], out.displacements));
      multipliers[t] += system.rho() * gap;
      out.constraint_error = std::max(out.constraint_error, gap.cwiseAbs().maxCoeff());
    }
    if (out.constraint_error <= 1e-12 * scale) break;
  }
  out.steps = std::min(out.steps, 100);
  return out;
}

// Of the given ties, those of the interface that scores highest (summed
// over its ties), and of any within 1e-6 of it.
std::vector<int> highest_interfaces(const std::vector<FeaContact>& ties, const std::vector<int>& candidates,
                                    const std::function<double(int)>& score) {
  std::map<int, double> total;
  for (int t : candidates) total[ties[t].interface] += score(t);
  double most = 0;
  for (const auto& [face, sum] : total) most = std::max(most, sum);
  std::vector<int> chosen;
  for (int t : candidates)
    if (total[ties[t].interface] >= (1 - 1e-6) * most) chosen.push_back(t);
  return chosen;
}

}  // namespace

FeaResult analyze_fea(const Structure& structure, const FeaMesh& mesh, const FeaSettings& settings) {
  const Clock::time_point start = Clock::now();
  check_settings(structure, settings);
  structure.require_free_block("fea");
  structure.require_detected_interfaces("fea");
  structure.require_no_overlaps(settings.contact, "fea");
  FeaResult result;
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(settings.contact);
  const std::vector<Interface>& interfaces = *interfaces_list;
  const double size = structure.bounds().diagonal();
  std::vector<const Block*> blocks;
  for (const StructureBlock& entry : structure.entries()) blocks.push_back(entry.block.get());
  std::vector<FeaContact> ties =
      contact_ties(structure, mesh, interfaces, effective_tolerance(blocks, settings.contact));
  std::vector<Vec3> normals;
  std::vector<double> sides;
  for (const FeaContact& tie : ties) {
    normals.push_back(interfaces[tie.interface].normal);
    sides.push_back(tie.block == interfaces[tie.interface].b ? 1.0 : -1.0);
  }
  const Assembly assembly = assemble(structure, mesh, settings.material);
  const int dofs = 3 * static_cast<int>(mesh.nodes().size());
  result.dofs = dofs;
  result.total_weight = assembly.total_weight;
  // Stop points between the long steps (CHOLMOD's analysis and each
  // factorisation run to their end): an interrupt waits one of them at most.
  const auto interrupted_before_solving = [&] {
    if (!stop_requested()) return false;
    result.status = FeaStatus::Interrupted;
    result.displacements.assign(mesh.nodes().size(), Vec3::Zero());
    result.max_displacement = result.max_penetration = std::numeric_limits<double>::quiet_NaN();
    result.seconds = seconds_since(start);
    return true;
  };
  if (interrupted_before_solving()) return result;
  TiedSystem system(assembly, ties, normals, dofs);
  result.factor_nonzeros = static_cast<long>(system.factor_nonzeros());
  if (interrupted_before_solving()) return result;

  Eigen::VectorXd displacements;
  std::vector<Vec3> multipliers(ties.size(), Vec3::Zero());
  std::vector<Hold> holds(ties.size(), Hold::All);
  const bool unilateral = settings.method == FeaContactModel::Unilateral;
  const double tension_threshold =
      ties.empty() ? 0 : settings.tension_tolerance * assembly.total_weight / static_cast<double>(ties.size());
  const double bound = settings.max_displacement * size;
  double elastic_scale = 0;  // m, the first solve's largest displacement

  // Solves the current contact state (holds) and says what violates it:
  // closed nodes in tension, open ones overlapping (unilateral).
  struct StateReport {
    FeaIteration iteration;
    std::vector<int> tensile, overlapping;
    bool interrupted = false, factorized = true, beyond_limit = false;
  };
  const auto solve_state = [&]() {
    const Clock::time_point solve_start = Clock::now();
    StateReport report;
    TiedSolution solution = solve_tied(system, ties, normals, holds, assembly.loads, multipliers);
    FeaIteration& iteration = report.iteration;
    iteration.active = static_cast<int>(std::count(holds.begin(), holds.end(), Hold::All));
    iteration.multiplier_steps = solution.steps;
    iteration.constraint_error = solution.constraint_error;
    report.interrupted = solution.interrupted;
    report.factorized = solution.factorized;
    if (solution.factorized && !solution.interrupted) {
      const double largest = solution.displacements.cwiseAbs().maxCoeff();
      if (elastic_scale == 0) elastic_scale = largest;
      report.beyond_limit = !(largest <= bound);
      for (size_t t = 0; t < ties.size(); ++t) {
        const double normal_force = -sides[t] * normals[t].dot(multipliers[t]);
        const double opening = sides[t] * normals[t].dot(tie_gap(ties[t], solution.displacements));
        ties[t].tensile = holds[t] == Hold::All && normal_force < -tension_threshold;
        if (ties[t].tensile) {
          report.tensile.push_back(static_cast<int>(t));
          iteration.tension -= normal_force;
          iteration.max_tension = std::max(iteration.max_tension, -normal_force);
        }
        if (holds[t] == Hold::Tangential && opening < -kOverlapTolerance * elastic_scale)
          report.overlapping.push_back(static_cast<int>(t));
      }
      iteration.tensile = static_cast<int>(report.tensile.size());
      displacements = std::move(solution.displacements);
    }
    iteration.seconds = seconds_since(solve_start);
    return report;
  };
  const auto change_holds = [&](const std::vector<int>& opened, const std::vector<int>& closed, Hold open_hold) {
    const int iteration = static_cast<int>(result.history.size());
    for (int t : opened) {
      holds[t] = open_hold;
      ties[t].released_at = iteration;
    }
    for (int t : closed) holds[t] = Hold::All;
    result.history.back().released += static_cast<int>(opened.size());
    result.history.back().engaged += static_cast<int>(closed.size());
  };
  const auto solves_left = [&] { return settings.max_relax_iterations - (static_cast<int>(result.history.size()) - 1); };

  if (!unilateral || !settings.relax) {
    // One tied solve, or the thesis's relaxation: release the nodes in
    // tension (both ways) and solve again until none is.
    for (;;) {
      const StateReport report = solve_state();
      result.history.push_back(report.iteration);
      if (report.interrupted) {
        result.status = FeaStatus::Interrupted;
        break;
      }
      if (!report.factorized || report.beyond_limit) {
        displacements.resize(0);  // the last equilibrium was of other ties
        result.status = FeaStatus::Mechanism;
        break;
      }
      if (report.tensile.empty()) {
        result.status = FeaStatus::CompressionOnly;
        break;
      }
      if (!settings.relax) {
        result.status = FeaStatus::Tension;
        break;
      }
      if (solves_left() <= 0) {
        result.status = FeaStatus::IterationLimit;
        break;
      }
      change_holds(settings.release == FeaRelease::Largest
                       ? highest_interfaces(ties, report.tensile,
                                            [&](int t) { return sides[t] * normals[t].dot(multipliers[t]); })
                       : report.tensile,
                   {}, Hold::None);
    }
  } else {
    // The primal-dual active-set iteration: open every closed node in
    // tension and close every open node that overlaps, at once. It ends in
    // a consistent state, which is the solution (the program is convex),
    // or returns to a state already solved; then, and after
    // kActiveSetSteps, the interior-point program finds the solution and
    // the iteration resumes from its contact state to make it exact.
    std::set<std::vector<Hold>> solved_states;
    const auto active_set = [&](int steps) {
      for (int step = 0;; ++step) {
        solved_states.insert(holds);
        const StateReport report = solve_state();
        result.history.push_back(report.iteration);
        if (report.interrupted) return FeaStatus::Interrupted;
        if (!report.factorized) return FeaStatus::Mechanism;  // round-off: the ground springs keep it definite
        if (report.tensile.empty() && report.overlapping.empty())
          return report.beyond_limit ? FeaStatus::Mechanism : FeaStatus::CompressionOnly;
        std::vector<Hold> next = holds;
        for (int t : report.tensile) next[t] = Hold::Tangential;
        for (int t : report.overlapping) next[t] = Hold::All;
        if (step >= steps || solves_left() <= 0 || solved_states.count(next)) return FeaStatus::IterationLimit;
        change_holds(report.tensile, report.overlapping, Hold::Tangential);
      }
    };
    result.status = active_set(kActiveSetSteps);
    if (result.status == FeaStatus::IterationLimit && solves_left() > 0) {
      std::vector<ContactRow> rows(ties.size());
      for (size_t t = 0; t < ties.size(); ++t) {
        const Interface& face = interfaces[ties[t].interface];
        rows[t].normal = face.normal;
        rows[t].tangent1 = face.u;
        rows[t].tangent2 = face.v;
        rows[t].side = sides[t];
        for_each_tie_entry(ties[t], [&](int node, double w) {
          rows[t].nodes.push_back(node);
          rows[t].weights.push_back(w);
        });
      }
      SparseMatrix stiffness(dofs, dofs);
      stiffness.setFromTriplets(assembly.stiffness.begin(), assembly.stiffness.end());
      const Eigen::VectorXd start = displacements;  // of the last state solved
      const ContactProgramResult program =
          solve_contact_program(stiffness, assembly.loads, rows, bound, std::max(elastic_scale, 1e-12 * size),
                                std::max(assembly.total_weight, 1e-300), start);
      result.interior_point_iterations = program.iterations;
      if (program.interrupted) {
        result.status = FeaStatus::Interrupted;
      } else if (program.solved && program.displacements.cwiseAbs().maxCoeff() >= 0.5 * bound) {
        result.status = FeaStatus::Mechanism;  // the displacements went to the bound
        displacements.resize(0);
      } else if (program.solved) {
        // Closed where the node's share of the largest force exceeds its
        // share of the largest opening.
        std::vector<double> openings(ties.size());
        double largest_force = 1e-300, largest_opening = 1e-300;
        for (size_t t = 0; t < ties.size(); ++t) {
          openings[t] = std::max(0.0, sides[t] * normals[t].dot(tie_gap(ties[t], program.displacements)));
          largest_force = std::max(largest_force, program.normal_forces[t]);
          largest_opening = std::max(largest_opening, openings[t]);
        }
        std::vector<int> opened, closed;
        for (size_t t = 0; t < ties.size(); ++t) {
          const bool pressed = program.normal_forces[t] / largest_force >= openings[t] / largest_opening;
          if (pressed && holds[t] != Hold::All) closed.push_back(static_cast<int>(t));
          if (!pressed && holds[t] == Hold::All) opened.push_back(static_cast<int>(t));
        }
        change_holds(opened, closed, Hold::Tangential);
        result.status = active_set(solves_left());
      }
    }
  }
  result.iterations = static_cast<int>(result.history.size()) - 1;
  result.compression_only = result.status == FeaStatus::CompressionOnly;
  const bool verdict = result.status == FeaStatus::CompressionOnly || result.status == FeaStatus::Tension;

  result.displacements.assign(mesh.nodes().size(), Vec3::Zero());
  if (displacements.size() == dofs)
    for (size_t n = 0; n < mesh.nodes().size(); ++n) result.displacements[n] = displacements.segment<3>(3 * n);
  for (const Vec3& u : result.displacements) result.max_displacement = std::max(result.max_displacement, u.norm());
  for (size_t t = 0; t < ties.size(); ++t) {
    FeaContact& tie = ties[t];
    // -lambda acts on the tied node; a tie on block a acts on a, so b gets +lambda.
    tie.force_on_b = holds[t] == Hold::None ? Vec3::Zero() : Vec3(-sides[t] * multipliers[t]);
    tie.normal_force = tie.force_on_b.dot(normals[t]);
    if (displacements.size() == dofs) tie.opening = sides[t] * normals[t].dot(tie_gap(tie, displacements));
    tie.released = holds[t] != Hold::All;
    if (tie.released) result.max_penetration = std::max(result.max_penetration, -tie.opening);
  }
  // Without a verdict the last solve is no equilibrium: its displacements
  // are 0 (not factorised, interrupted) or anything at all, so they
  // measure nothing.
  if (!verdict) {
    result.max_displacement = std::numeric_limits<double>::quiet_NaN();
    result.max_penetration = std::numeric_limits<double>::quiet_NaN();
  }

  result.interfaces.assign(interfaces.size(), FeaInterfaceForce{});
  std::vector<Vec3> pressure_moment(interfaces.size(), Vec3::Zero());
  std::vector<double> pressure(interfaces.size(), 0.0);
  for (const FeaContact& tie : ties) {
    FeaInterfaceForce& sum = result.interfaces[tie.interface];
    ++sum.contacts;
    if (tie.released) ++sum.released;
    sum.resultant += tie.force_on_b;  // an open node may still carry a tangential force (unilateral)
    if (tie.normal_force >= 0) sum.compression += tie.normal_force;
    else sum.tension -= tie.normal_force;
    pressure_moment[tie.interface] += tie.normal_force * mesh.nodes()[tie.node];
    pressure[tie.interface] += tie.normal_force;
  }
  for (size_t k = 0; k < interfaces.size(); ++k) {
    FeaInterfaceForce& sum = result.interfaces[k];
    sum.center_of_pressure = std::abs(pressure[k]) > 1e-12 * std::max(assembly.total_weight, 1e-300)
                                 ? Vec3(pressure_moment[k] / pressure[k])
                                 : interfaces[k].center;
  }
  result.contacts = std::move(ties);

  if (settings.stresses && displacements.size() == dofs) {
    result.stresses.reserve(mesh.elements().size());
    for (int e = 0; e < static_cast<int>(mesh.elements().size()); ++e) {
      HexVector u;
      for (int a = 0; a < 8; ++a) u.segment<3>(3 * a) = result.displacements[mesh.elements()[e][a]];
      result.stresses.push_back(hex_stress(mesh.element_nodes(e), u, settings.material));
    }
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace ashlar
