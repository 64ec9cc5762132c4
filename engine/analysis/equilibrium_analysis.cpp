#include "analysis/equilibrium_analysis.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "analysis/verdict_notes.hpp"
#include "core/clock.hpp"

namespace ashlar {

double fill_result_forces(const Structure& structure, const EquilibriumProblem& problem, const Eigen::VectorXd& x,
                          EquilibriumResult& result) {
  const std::vector<Interface>& interfaces = *problem.interfaces;
  result.interfaces.resize(interfaces.size());
  for (size_t i = 0; i < interfaces.size(); ++i) {
    result.interfaces[i].a = interfaces[i].a;
    result.interfaces[i].b = interfaces[i].b;
  }
  std::vector<double> pressure_weight(interfaces.size(), 0.0);
  std::vector<Vec3> pressure_moment(interfaces.size(), Vec3::Zero());
  result.block_tension.assign(structure.size(), 0.0);
  const double wu = problem.weight_unit;
  result.cables.resize(structure.cables().size());
  result.virtual_torques.assign(structure.size(), Vec3::Zero());
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  double penalised = 0.0;  // scaled
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& v = problem.groups[k];
    const Eigen::Vector4d scaled = x.segment<4>(4 * static_cast<Eigen::Index>(k));
    // The penalised unknowns are bounded below by 0; an iterate short of
    // convergence may still sit a little outside, which must not make the
    // infeasibility negative.
    penalised += problem.rules_of(v).linear.dot(scaled.cwiseMax(0.0));
    if (v.kind == GroupKind::cable || v.kind == GroupKind::bounded_cable) {
      result.cables[v.source].tension = (scaled(0) - scaled(1)) * wu;
      result.cables[v.source].compression = scaled(1) * wu;
      continue;
    }
    if (v.kind == GroupKind::slack) {
      if (v.block_a >= 0 && rows[v.component] >= 3) {
        result.virtual_torques[v.block_a](rows[v.component] - 3) =
            (scaled(0) - scaled(1)) * wu * problem.length_unit;
      }
      continue;
    }
    const Eigen::Vector4d forces = scaled * wu;
    const Interface& contact = interfaces[v.source];
    InterfaceForces& through = result.interfaces[v.source];
    const double normal = forces(0) - forces(1);
    through.compression += forces(0);
    through.tension += forces(1);
    through.normal_force += normal;
    through.resultant += normal * contact.normal + forces(2) * contact.u + forces(3) * contact.v;
    pressure_weight[v.source] += normal;
    const Vec3& position = problem.vertex_position(v);
    pressure_moment[v.source] += normal * position;
    result.block_tension[v.block_a] += forces(1);
    result.block_tension[v.block_b] += forces(1);
    result.vertex_forces.push_back(forces);
    result.vertex_positions.push_back(position);
    result.vertex_interface.push_back(v.source);
  }
  for (size_t i = 0; i < interfaces.size(); ++i) {
    result.interfaces[i].center_of_pressure = pressure_weight[i] > 0.0
                                                  ? Vec3(pressure_moment[i] / pressure_weight[i])
                                                  : interfaces[i].center;
  }
  return penalised;
}

EquilibriumAnalysis::EquilibriumAnalysis(const Structure& structure, const AnalysisSettings& settings,
                                         SolverCores cores)
    : cores_(cores) {
  update(structure, settings);
}

EquilibriumAnalysis::EquilibriumAnalysis(EquilibriumProblem problem, const AnalysisSettings& settings,
                                         SolverCores cores)
    : settings_(settings), cores_(cores), problem_(std::move(problem)) {
  const auto start = Clock::now();
  check_analysis_settings(settings);
  fit_solver();
  setup_seconds_ = seconds_since(start);
}

EquilibriumAnalysis::~EquilibriumAnalysis() = default;

void EquilibriumAnalysis::update(const Structure& structure, const AnalysisSettings& settings) {
  const auto start = Clock::now();
  check_analysis_settings(settings);
  problem_ = build_equilibrium_problem(structure, settings.problem);
  structure_ = &structure;
  settings_ = settings;
  floating_gaps_.clear();
  floating_gaps_found_ = false;
  fit_solver();
  setup_seconds_ = seconds_since(start);
}

void EquilibriumAnalysis::fit_solver() {
  if (!solver_ || !solver_->fits(problem_)) {
    solver_ = std::make_unique<EquilibriumSolver>(problem_, cores_);
    ++symbolic_analyses_;
  }
}

void EquilibriumAnalysis::set_rhs(Eigen::VectorXd rhs) {
  if (rhs.size() != problem_.row_count) {
    throw std::invalid_argument("set_rhs: " + std::to_string(problem_.row_count) + " rows expected, got " +
                                std::to_string(rhs.size()));
  }
  problem_.rhs = std::move(rhs);
}

void EquilibriumAnalysis::update_loads(const Structure& structure) {
  const auto start = Clock::now();
  set_rhs(load_rhs(structure, problem_));
  structure_ = &structure;
  setup_seconds_ += seconds_since(start);
}

void EquilibriumAnalysis::set_group(int k, const ForceGroup& group) {
  if (k < 0 || k >= static_cast<int>(problem_.groups.size())) {
    throw std::invalid_argument("set_group: no group " + std::to_string(k));
  }
  ForceGroup& old = problem_.groups[k];
  if (group.kind != old.kind) throw std::invalid_argument("set_group: group " + std::to_string(k) + " changes kind");
  const bool moved = group.row_a != old.row_a || group.row_b != old.row_b;
  old = group;
  if (moved && !solver_->refit(problem_)) {
    solver_ = std::make_unique<EquilibriumSolver>(problem_, cores_);
    ++symbolic_analyses_;
  }
}

void EquilibriumAnalysis::set_rules(GroupKind kind, GroupRules rules) {
  GroupRules& old = problem_.rules[static_cast<int>(kind)];
  if (rules.rows.rows() != old.rows.rows()) {
    throw std::invalid_argument("set_rules: " + std::to_string(old.rows.rows()) + " rows expected, got " +
                                std::to_string(rules.rows.rows()));
  }
  old = std::move(rules);
}

void EquilibriumAnalysis::set_shear_strengths(const std::vector<double>& strengths) {
  if (strengths.size() != static_cast<size_t>(problem_.contact_vertex_count)) {
    throw std::logic_error("set_shear_strengths: one strength per contact vertex needed");
  }
  for (size_t k = 0; k < strengths.size(); ++k) problem_.groups[k].bound = strengths[k];
}

bool EquilibriumAnalysis::prepare_response() {
  return !has_no_answer(last_status_) && solver_->prepare_response(problem_, solution_);
}

InteriorPointInfo EquilibriumAnalysis::solve_qp(const InteriorPointSettings& solver, bool warm_start) {
  const InteriorPointInfo info = solver_->solve(problem_, solver, solution_, warm_start);
  last_status_ = info.status;
  return info;
}

bool EquilibriumAnalysis::carries_alone(Eigen::VectorXd load, int max_iterations, int& iterations) {
  set_rhs(std::move(load));
  InteriorPointSettings verdict;
  verdict.max_iterations = max_iterations;
  verdict.certify_below = settings_.stable_tolerance;
  const InteriorPointInfo info = solve_qp(verdict, false);
  iterations = info.iterations;
  return info.status == SolverStatus::certified;
}

namespace {

// What the optimum's multipliers leave moving at a joint that does not move,
// in the program's dual units (mechanism.hpp: dual_unit). At the optimum a
// vertex carrying a force x (compression or friction, scaled) closes or
// slips at force_weight / n * x, the force regularisation's gradient, where
// a vertex that must open (it carries the tension the verdict needs) opens
// at 1 or more, the linear penalty's; the solver's tolerance bounds the
// rest. Ten times their sum: the arch at 1.02 times its load factor keeps
// its four hinges and drops the joints that closed or slipped at a few
// 1e-7 of the fastest block.
double limit_noise(const AnalysisSettings& settings, const EquilibriumProblem& problem, const Eigen::VectorXd& x) {
  constexpr double kMargin = 10.0;
  const double largest = x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0;
  return kMargin * (settings.problem.force_weight / std::max(problem.body_count, 1) * largest +
                    settings.solver.tolerance);
}

}  // namespace

EquilibriumResult EquilibriumAnalysis::solve(bool warm_start) {
  if (!structure_) throw std::logic_error("EquilibriumAnalysis::solve: a QP without a structure (solve_qp)");
  if (!floating_gaps_found_ && !problem_.floating_blocks.empty()) {  // part of the setup
    const auto start = Clock::now();
    // Near misses only: a gap of over 1 % of the structure is not one.
    floating_gaps_ = structure_->missed_contacts(problem_.floating_blocks, kNearMiss * structure_->bounds().diagonal(),
                                                 settings_.problem.contact);
    setup_seconds_ += seconds_since(start);
  }
  floating_gaps_found_ = true;
  const auto start = Clock::now();
  EquilibriumResult result;
  result.timings.setup = setup_seconds_;
  InteriorPointSettings solver_settings = settings_.solver;
  if (settings_.verdict_only) solver_settings.certify_below = settings_.stable_tolerance;
  const InteriorPointInfo info = solve_qp(solver_settings, warm_start);
  result.status = info.status;
  result.iterations = info.iterations;
  result.factorizations = info.factorizations;
  result.objective = info.objective;
  result.timings.assembly = info.assembly_seconds;
  result.timings.factorization = info.factorization_seconds;
  result.timings.solve = info.solve_seconds;
  result.floating_blocks = problem_.floating_blocks;
  result.floating_gaps = floating_gaps_;

  const std::vector<Interface>& interfaces = *problem_.interfaces;
  const Eigen::VectorXd& x = solution_.x;
  const double penalised = fill_result_forces(*structure_, problem_, x, result);
  result.imbalance_without_tension = compression_only_imbalance(problem_, x);
  // Stability is a question of feasibility: forces that balance every block
  // without tension prove it, converged or not. Without such forces only a
  // converged optimum (whose tension is then needed) proves instability.
  const bool floating = problem_.has_floating_bodies();
  result.stable = !floating && result.status != SolverStatus::interrupted &&
                  result.imbalance_without_tension <= settings_.stable_tolerance;
  result.borderline = !floating &&
                      result.imbalance_without_tension > settings_.stable_tolerance * kBorderlineBelow &&
                      result.imbalance_without_tension <= settings_.stable_tolerance * kBorderlineAbove;
  // Floating blocks cannot be balanced at all; a numerical failure (also what
  // a problem with no equilibrium even with tension, e.g. no friction under
  // a sideways load, ends in) leaves no usable equilibrium either.
  const int bodies = std::max(problem_.body_count, 1);
  if (floating || has_no_answer(result.status)) {
    result.infeasibility = std::numeric_limits<double>::infinity();
    result.penalty = std::numeric_limits<double>::infinity();
  } else {
    result.infeasibility = result.stable ? 0.0 : penalised / bodies;
    result.penalty = info.objective / bodies;
    if (!result.stable) {
      double dual_unit = 0.0;
      result.mechanism = mechanism_of(*structure_, problem_, solution_.y.data(), &dual_unit);
      result.limit = limit_interfaces(*structure_, interfaces, result.mechanism,
                                      dual_unit > 0.0 ? limit_noise(settings_, problem_, x) / dual_unit : 0.0);
    }
  }
  result.seconds = setup_seconds_ + seconds_since(start);
  setup_seconds_ = 0.0;  // counted once, by the first solve after it
  return result;
}

EquilibriumAnalysis& AnalysisSequence::set_up(const Structure& structure) {
  if (analysis_) analysis_->update(structure, settings_);
  else analysis_ = std::make_unique<EquilibriumAnalysis>(structure, settings_);
  return *analysis_;
}

EquilibriumResult AnalysisSequence::analyze(const Structure& structure) {
  const bool warm = warm_start_ && has_optimum_ && optimum_blocks_ == structure.size();
  EquilibriumResult result = set_up(structure).solve(warm);
  has_optimum_ = result.status == SolverStatus::converged || result.status == SolverStatus::inaccurate;
  optimum_blocks_ = structure.size();
  return result;
}

}  // namespace ashlar
