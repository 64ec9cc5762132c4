#include "analysis/interior_point.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "analysis/best_iterate.hpp"
#include "analysis/group_passes.hpp"
#include "analysis/iterate_residuals.hpp"
#include "analysis/newton_system.hpp"
#include "analysis/step_policy.hpp"
#include "core/clock.hpp"
#include "core/interrupt.hpp"

namespace ashlar {

namespace {

SparseCholeskyOptions factorisation_for(SolverCores cores) {
  SparseCholeskyOptions factorisation;
  if (cores == SolverCores::one) factorisation.split_from_rows = std::numeric_limits<int>::max();
  return factorisation;
}

}  // namespace

const char* status_name(SolverStatus status) {
  return kSolverStatusNames.name(status);
}

EquilibriumSolver::EquilibriumSolver(const EquilibriumProblem& problem, SolverCores cores)
    : loop_(cores == SolverCores::one ? 1 : 0), normal_(problem, loop_, factorisation_for(cores)) {}

EquilibriumSolver::~EquilibriumSolver() = default;

bool EquilibriumSolver::fits(const EquilibriumProblem& problem) const {
  return normal_.fits(problem);
}

bool EquilibriumSolver::refit(const EquilibriumProblem& problem) {
  if (fits(problem)) return true;
  if (!normal_.refit(problem)) return false;
  twins_.clear();  // classes of the old groups
  response_ready_ = false;
  return true;
}

void EquilibriumSolver::find_twins(const EquilibriumProblem& problem, bool merge) {
  if (twins_.find(problem, normal_.block_rows(), merge)) normal_.work_on(twins_);
}

bool EquilibriumSolver::prepare_response(const EquilibriumProblem& problem,
                                         const InteriorPointSolution& solution, bool merge) {
  response_ready_ = false;
  if (!normal_.analysed()) return false;
  const std::vector<int> first_row = problem.inequality_starts();
  const int m_total = first_row.back();
  if (solution.w.size() != m_total || solution.z.size() != m_total) return false;
  find_twins(problem, merge);
  if (!twins_.merged()) {
    normal_.assemble_any(problem, first_row, solution.w, solution.z, twins_, response_phi_);
  } else {
    InteriorPointSolution merged;
    twins_.merge_solution(solution, first_row, merged);
    normal_.assemble_any(twins_.merge(problem), twins_.merged_first_rows(first_row), merged.w, merged.z, twins_,
                         response_phi_);
  }
  response_ready_ = normal_.factorize_shifted();
  return response_ready_;
}

Eigen::VectorXd EquilibriumSolver::multiplier_response(const Eigen::VectorXd& delta_rhs) const {
  if (!response_ready_) throw std::logic_error("multiplier_response before prepare_response");
  return normal_.solve(delta_rhs);
}

Eigen::Vector4d EquilibriumSolver::group_response(const EquilibriumProblem& problem, int group,
                                                  const Eigen::VectorXd& multipliers) const {
  const Eigen::Vector4d reaction = problem.reaction(problem.groups[group], multipliers);
  if (!twins_.merged()) return solve_phi(response_phi_[group], reaction);
  // A class of m twins has Phi m times a twin's, and m times its reaction.
  const int merged = twins_.class_of(group);
  return solve_phi(response_phi_[merged], twins_.count(merged) * reaction);
}

InteriorPointInfo EquilibriumSolver::solve(const EquilibriumProblem& problem,
                                           const InteriorPointSettings& settings,
                                           InteriorPointSolution& solution, bool warm_start) {
  find_twins(problem, settings.merge_twins);
  if (!twins_.merged()) return solve_groups(problem, settings, solution, warm_start);
  const std::vector<int> first_row = problem.inequality_starts();
  const bool warm = warm_start && solution.x.size() == problem.variable_count() &&
                    solution.y.size() == normal_.rows() && solution.w.size() == first_row.back() &&
                    solution.z.size() == first_row.back();
  InteriorPointSolution merged;
  if (warm) twins_.merge_solution(solution, first_row, merged);
  InteriorPointInfo info = solve_groups(twins_.merge(problem), settings, merged, warm);
  twins_.split_solution(merged, first_row, solution);
  // The mean complementarity of the problem's rows: the total gap is the
  // same, over more rows.
  if (first_row.back() > 0) info.complementarity *= static_cast<double>(merged.w.size()) / first_row.back();
  return info;
}

InteriorPointInfo EquilibriumSolver::solve_groups(const EquilibriumProblem& problem,
                                                  const InteriorPointSettings& settings,
                                                  InteriorPointSolution& solution, bool warm_start) {
  return normal_.block_rows() == 3 ? solve_rows<3>(problem, settings, solution, warm_start)
                                   : solve_rows<6>(problem, settings, solution, warm_start);
}

template <int D>
InteriorPointInfo EquilibriumSolver::solve_rows(const EquilibriumProblem& problem,
                                                const InteriorPointSettings& settings,
                                                InteriorPointSolution& solution, bool warm_start) {
  InteriorPointInfo info;
  const int nv = static_cast<int>(problem.groups.size());
  const int balance_rows = normal_.rows();
  const InequalityRows inequality{problem.inequality_starts()};
  const int m_total = inequality.total();
  const bool sizes_match = solution.x.size() == 4 * nv && solution.y.size() == balance_rows &&
                           solution.w.size() == m_total && solution.z.size() == m_total;
  const bool cold_start = !(warm_start && sizes_match);
  start_iterate(problem, inequality, balance_rows, !cold_start, solution);
  if (nv == 0 && balance_rows == 0) {
    info.status = SolverStatus::converged;
    return info;
  }
  if (!normal_.analysed()) {
    info.status = SolverStatus::numerical_error;
    return info;
  }

  GroupPasses passes(loop_, nv, balance_rows);
  IterateResiduals residuals(problem, inequality, twins_, passes);
  NewtonSystem<D> newton(problem, inequality, twins_, normal_, passes, solution);
  // The residuals at the iterate (the Newton right-hand side's x and y
  // parts; the newton system makes its w and z parts as it solves) and a
  // Newton direction.
  NewtonVectors r = NewtonVectors::sized(nv, balance_rows, 0);
  NewtonVectors direction = NewtonVectors::sized(nv, balance_rows, m_total);
  BestIterate best(solution, direction, settings.inaccurate_tolerance);
  const int factorizations_before = normal_.factorizations();

  bool starting = cold_start;
  for (int iteration = 0;; ++iteration) {
    auto start = Clock::now();
    const double duality_gap = residuals.measure<D>(solution, r, info);
    const double mu = info.complementarity;
    info.iterations = iteration;
    best.begin(iteration);
    if (!std::isfinite(mu) || !std::isfinite(info.primal_residual) || !std::isfinite(info.dual_residual)) {
      best.keep_previous();
      info.status = SolverStatus::numerical_error;
      break;
    }
    const double error_now = residuals.scaled_error(info, duality_gap, settings.objective_floor, solution.x);
    if (error_now <= settings.tolerance) {
      info.status = SolverStatus::converged;
      break;
    }
    if (settings.certify_below > 0.0 && !starting &&
        compression_only_imbalance(problem, solution.x) <= settings.certify_below) {
      info.status = SolverStatus::certified;
      break;
    }
    best.note(iteration, error_now, !starting, info);
    if (best.stalled(iteration) || iteration >= settings.max_iterations) {
      info.status = SolverStatus::max_iterations;
      break;
    }
    if (stop_requested()) {
      info.status = SolverStatus::interrupted;
      break;
    }

    newton.assemble();
    info.assembly_seconds += seconds_since(start);
    start = Clock::now();
    const bool factored = newton.factor();
    info.factorization_seconds += seconds_since(start);
    if (!factored) {
      info.status = SolverStatus::numerical_error;
      break;
    }

    // Predictor: the affine-scaling direction. It only sets the centring
    // and the second-order term (and, at a cold start, the heuristic
    // starting point), so it is not refined: the corrector, the step taken,
    // is.
    start = Clock::now();
    newton.direction(r, {}, direction, NewtonSystem<D>::kNoRefinement);
    info.solve_seconds += seconds_since(start);
    if (starting) {
      starting = false;
      take_mehrotra_start(direction, solution);
      continue;
    }
    // Corrector: second-order term and centring, same factorisation.
    const double centring = corrector_centring(solution, direction, mu);
    start = Clock::now();
    newton.direction(r, {true, centring}, direction, error_now);
    info.solve_seconds += seconds_since(start);
    StepLengths step;
    if (!choose_step_lengths(problem, solution, direction, settings.step_fraction, error_now,
                             residuals.dual_scale(), step)) {
      info.status = SolverStatus::numerical_error;
      break;
    }
    take_step(direction, step, solution);
    best.stepped(step);
  }
  best.restore(info, solution);
  info.factorizations = normal_.factorizations() - factorizations_before;
  info.groups = nv;
  info.objective = residuals.objective(solution.x);
  return info;
}

}  // namespace ashlar
