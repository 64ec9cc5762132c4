#include "fea/fea.hpp"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/sparse_cholesky.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"

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

// K + rho A^T A over one fixed pattern (every tie, released ones as zeros),
// so CHOLMOD analyses the ordering once and each release only refactorises
// from K's values plus the active ties' terms, placed once.
class TiedSystem {
public:
  TiedSystem(const Assembly& assembly, const std::vector<FeaContact>& ties, int dofs) : ties_(ties) {
    // A stiff penalty makes each multiplier update contract the constraint
    // error ~1/ratio; 1e4 keeps K + rho A^T A well inside double precision.
    rho_ = 1e4 * std::max(assembly.mean_diagonal, 1e-300);
    std::vector<Triplet> entries = assembly.stiffness;
    for_each_tie_term([&](size_t, int row, int col, double) { entries.emplace_back(row, col, 0.0); });
    SparseMatrix m(dofs, dofs);
    m.setFromTriplets(entries.begin(), entries.end());
    m.makeCompressed();
    stiffness_values_.assign(m.valuePtr(), m.valuePtr() + m.nonZeros());
    for_each_tie_term([&](size_t t, int row, int col, double value) {
      const int* first = m.innerIndexPtr() + m.outerIndexPtr()[col];
      const int* last = m.innerIndexPtr() + m.outerIndexPtr()[col + 1];
      tie_terms_.push_back({t, static_cast<int>(std::lower_bound(first, last, row) - m.innerIndexPtr()), value});
    });
    std::vector<int> starts(m.outerIndexPtr(), m.outerIndexPtr() + dofs + 1);
    std::vector<int> rows(m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
    cholesky_ = std::make_unique<SparseCholesky>(dofs, std::move(starts), std::move(rows));
  }

  double rho() const { return rho_; }
  double factor_nonzeros() const { return cholesky_->factor_nonzeros(); }

  bool factorize(const std::vector<bool>& active) {
    double* values = cholesky_->values();
    std::copy(stiffness_values_.begin(), stiffness_values_.end(), values);
    for (const TieTerm& term : tie_terms_)
      if (active[term.tie]) values[term.position] += rho_ * term.value;
    return cholesky_->factorize();
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const { return cholesky_->solve(rhs); }

private:
  struct TieTerm {
    size_t tie;
    int position;  // into the pattern's values
    double value;  // of A^T A, without rho
  };

  // Upper-triangle entries (row <= col) of each tie's A_t^T A_t.
  template <class Visit>
  void for_each_tie_term(Visit&& visit) const {
    for (size_t t = 0; t < ties_.size(); ++t)
      for_each_tie_entry(ties_[t], [&](int p, double wp) {
        for_each_tie_entry(ties_[t], [&](int q, double wq) {
          if (p <= q)
            for (int d = 0; d < 3; ++d) visit(t, 3 * p + d, 3 * q + d, wp * wq);
        });
      });
  }

  const std::vector<FeaContact>& ties_;
  double rho_ = 0;
  std::vector<double> stiffness_values_;
  std::vector<TieTerm> tie_terms_;
  std::unique_ptr<SparseCholesky> cholesky_;
};

struct TiedSolution {
  Eigen::VectorXd displacements;
  std::vector<Vec3> multipliers;  // per tie; zero when released
  int steps = 0;
  double constraint_error = 0;
  bool factorized = false;
};

// Method of multipliers on the one factorisation: u solves
// (K + rho A^T A) u = f - A^T lambda, then lambda += rho A u, until A u = 0
// to round-off; the limit is the KKT solution of equation 9.
TiedSolution solve_tied(TiedSystem& system, const std::vector<FeaContact>& ties,
                        const std::vector<bool>& active, const Eigen::VectorXd& loads) {
  TiedSolution out;
  out.multipliers.assign(ties.size(), Vec3::Zero());
  out.factorized = system.factorize(active);
  if (!out.factorized) return out;
  for (out.steps = 1; out.steps <= 100; ++out.steps) {
    Eigen::VectorXd rhs = loads;
    for (size_t t = 0; t < ties.size(); ++t)
      if (active[t])
        for_each_tie_entry(ties[t], [&](int node, double w) { rhs.segment<3>(3 * node) -= w * out.multipliers[t]; });
    out.displacements = system.solve(rhs);
    const double scale = std::max(out.displacements.cwiseAbs().maxCoeff(), 1e-300);
    out.constraint_error = 0;
    for (size_t t = 0; t < ties.size(); ++t) {
      if (!active[t]) continue;
      const Vec3 gap = tie_gap(ties[t], out.displacements);
      out.multipliers[t] += system.rho() * gap;
      out.constraint_error = std::max(out.constraint_error, gap.cwiseAbs().maxCoeff());
    }
    if (out.constraint_error <= 1e-12 * scale) break;
  }
  out.steps = std::min(out.steps, 100);
  return out;
}

// The tensile ties of the interface whose ties carry the most tension, and
// of any interface within 1e-6 of it.
std::vector<int> most_tensile_interfaces(const std::vector<FeaContact>& ties, const std::vector<int>& tensile) {
  std::map<int, double> tension;
  for (int t : tensile) tension[ties[t].interface] -= ties[t].normal_force;
  double most = 0;
  for (const auto& [face, sum] : tension) most = std::max(most, sum);
  std::vector<int> chosen;
  for (int t : tensile)
    if (tension[ties[t].interface] >= (1 - 1e-6) * most) chosen.push_back(t);
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
  const Assembly assembly = assemble(structure, mesh, settings.material);
  const int dofs = 3 * static_cast<int>(mesh.nodes().size());
  result.dofs = dofs;
  result.total_weight = assembly.total_weight;
  TiedSystem system(assembly, ties, dofs);
  result.factor_nonzeros = static_cast<long>(system.factor_nonzeros());

  const double tension_threshold =
      ties.empty() ? 0 : settings.tension_tolerance * assembly.total_weight / static_cast<double>(ties.size());
  std::vector<bool> active(ties.size(), true);
  TiedSolution solution;
  for (int solve = 0;; ++solve) {
    const Clock::time_point solve_start = Clock::now();
    solution = solve_tied(system, ties, active, assembly.loads);
    FeaIteration iteration;
    iteration.active = static_cast<int>(std::count(active.begin(), active.end(), true));
    iteration.multiplier_steps = solution.steps;
    iteration.constraint_error = solution.constraint_error;
    const double largest = solution.factorized ? solution.displacements.cwiseAbs().maxCoeff() : 0;
    if (!solution.factorized || !(largest <= settings.max_displacement * size)) {
      iteration.seconds = seconds_since(solve_start);
      result.history.push_back(iteration);
      result.status = FeaStatus::Mechanism;
      break;
    }
    std::vector<int> tensile;
    for (size_t t = 0; t < ties.size(); ++t) {
      FeaContact& tie = ties[t];
      // -lambda acts on the tied node; a tie on block a acts on a, so b gets +lambda.
      tie.force_on_b = active[t] ? (tie.block == interfaces[tie.interface].b ? -solution.multipliers[t]
                                                                              : solution.multipliers[t])
                                 : Vec3::Zero();
      tie.normal_force = tie.force_on_b.dot(interfaces[tie.interface].normal);
      tie.tensile = active[t] && tie.normal_force < -tension_threshold;
      if (tie.tensile) {
        tensile.push_back(static_cast<int>(t));
        iteration.tension -= tie.normal_force;
        iteration.max_tension = std::max(iteration.max_tension, -tie.normal_force);
      }
    }
    iteration.tensile = static_cast<int>(tensile.size());
    iteration.seconds = seconds_since(solve_start);
    result.history.push_back(iteration);
    if (tensile.empty()) {
      result.status = FeaStatus::CompressionOnly;
      break;
    }
    if (!settings.relax || solve >= settings.max_relax_iterations) {
      result.status = FeaStatus::Tension;
      break;
    }
    if (settings.release == FeaRelease::Largest) tensile = most_tensile_interfaces(ties, tensile);
    for (int t : tensile) {
      active[t] = false;
      ties[t].released = true;
      ties[t].released_at = solve + 1;
    }
  }
  result.iterations = static_cast<int>(result.history.size()) - 1;
  result.compression_only = result.status == FeaStatus::CompressionOnly;

  result.displacements.assign(mesh.nodes().size(), Vec3::Zero());
  if (solution.factorized)
    for (size_t n = 0; n < mesh.nodes().size(); ++n) result.displacements[n] = solution.displacements.segment<3>(3 * n);
  for (const Vec3& u : result.displacements) result.max_displacement = std::max(result.max_displacement, u.norm());
  // A mechanism's last solve is no equilibrium: its displacements are 0
  // (not factorised) or past the limit by any amount, so they measure nothing.

  result.interfaces.assign(interfaces.size(), FeaInterfaceForce{});
  std::vector<Vec3> pressure_moment(interfaces.size(), Vec3::Zero());
  std::vector<double> pressure(interfaces.size(), 0.0);
  for (size_t t = 0; t < ties.size(); ++t) {
    FeaContact& tie = ties[t];
    FeaInterfaceForce& sum = result.interfaces[tie.interface];
    ++sum.contacts;
    if (solution.factorized) {
      const Vec3 gap = tie_gap(tie, solution.displacements);  // own node minus the touched point
      const Vec3& n = interfaces[tie.interface].normal;
      tie.opening = tie.block == interfaces[tie.interface].a ? -gap.dot(n) : gap.dot(n);
    }
    if (tie.released) {
      ++sum.released;
      result.max_penetration = std::max(result.max_penetration, -tie.opening);
      continue;
    }
    sum.resultant += tie.force_on_b;
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
  // A mechanism's last solve is no equilibrium: its displacements are 0
  // (not factorised) or past the limit by any amount, so they measure nothing.
  if (result.status == FeaStatus::Mechanism) {
    result.max_displacement = std::numeric_limits<double>::quiet_NaN();
    result.max_penetration = std::numeric_limits<double>::quiet_NaN();
  }

  if (settings.stresses && solution.factorized) {
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
