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

// Finishing by the active set (polish, below) is tried from this scaled
// error on, and again only once the error has fallen by kPolishProgress
// since the last try that failed. The 10,051-block walls polish at their
// first try, at an error of 7.8e-4 (3D) and 4.8e-4 (planar): 18-19
// iterations became 11 (13 from 1e-4).
constexpr double kPolishBelow = 1e-3;
constexpr double kPolishProgress = 0.1;
// The slacks of the rows taken as active, and the multipliers of the
// others, are multiplied by this (a power of two: undone exactly) for the
// polishing step: the Newton system then holds the first as equalities and
// drops the others, to about this relative accuracy (2^-27, about 1e-8,
// left every step of the walls 3e-8 off; 2^-53 leaves the first tries 3 off).
const double kSharpening = std::ldexp(1.0, -40);
// The least slack and multiplier of a polished iterate (scaled units): the
// step sets the active rows' slacks and the others' multipliers to about
// 0, either side; the solver's later uses (warm starts, the response's
// z / w) need them positive.
constexpr double kPolishedFloor = 1e-20;
// The polish is tried only when the iterate tells the optimum's active
// set: every row's slack and multiplier at least kPolishSeparation apart
// (the larger over the smaller: the iterate's separation), and at least
// kSeparationGrowth times further apart than at the iteration before.
// Strictly complementary rows part by the factor mu falls each iteration
// (the 10,051-block walls 3e5 -> 1.7e6 -> 8.7e6 as the error fell to 3e-5);
// where the force weight's tie-break (1e-4 / bodies) is not resolved at
// the tolerance, rows draw together instead: the 100,052-block vault
// 7.9e5 -> 1.6e4 -> 1.1e4 -> 2.0e3 -> 3.5, a 24-voussoir arch 625 -> 1.6,
// a 16 x 18 dome 9.8e3 -> 773 -> 1.0, the 1,008-block vault 1.1e3 -> 1.2.
// There every polish fails (its forces break dropped friction rows by
// 0.1-1.5, scaled), a factorisation lost: the 100,052-block vault's at a
// separation of 1.1e4. The separation is measured from an error of
// kSeparationFrom on, so that a try always has the iteration before to
// compare with (the 100,052-block vault reaches 1e-3 at 7.9e5).
constexpr double kPolishSeparation = 1e4;
constexpr double kSeparationGrowth = 2.0;
constexpr double kSeparationFrom = 1e-2;

// Whether row i is taken as active by the polish: its multiplier larger
// than its slack.
bool taken_active(const InteriorPointSolution& iterate, Eigen::Index i) { return iterate.z(i) > iterate.w(i); }

// Multiplies the slack of each row taken as active by `factor`, and the
// multiplier of every other row. A row's two values keep their order, so
// applied with 1 / factor it undoes itself exactly.
void sharpen(double factor, InteriorPointSolution& iterate) {
  for (Eigen::Index i = 0; i < iterate.w.size(); ++i) {
    if (taken_active(iterate, i)) iterate.w(i) *= factor;
    else iterate.z(i) *= factor;
  }
}

// Finite termination (the active-set polish of OSQP; for interior points
// Ye 1992): near the optimum of these degenerate programs the error falls
// by only about a factor 8 an iteration (the products w_i z_i of rows that
// are neither clearly active nor clearly inactive shrink slowly), though
// the active set is known well before. The Newton step with the rows taken
// as active held as equalities and the others dropped, taken whole, lands
// on the optimum when the guess is right. Its forces and balance
// multipliers are the step's; the active rows' multipliers are solved
// group by group from the dual residual's equation instead (the step's
// own divide by the sharpened slacks, and lose every digit), the other
// rows' are 0, and the slacks G x - lower (0 for active rows).
template <int D>
class ActiveSetPolish {
public:
  ActiveSetPolish(const EquilibriumProblem& problem, const InequalityRows& inequality, const TwinGroups& twins,
                  GroupPasses& passes, NewtonSystem<D>& newton, IterateResiduals& residuals)
      : problem_(problem), inequality_(inequality), twins_(twins), passes_(passes), newton_(newton),
        residuals_(residuals) {}

  // The iterate's separation (kPolishSeparation).
  static double separation(const InteriorPointSolution& iterate) {
    double least = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < iterate.w.size(); ++i) {
      least = std::min(least, std::max(iterate.w(i), iterate.z(i)) / std::min(iterate.w(i), iterate.z(i)));
    }
    return least;
  }

  // Tries the polish from `iterate` (scaled error `iterate_error`, info
  // `info`, residuals `r`); `candidate` is the iteration's direction, used
  // as the polished point's room. When the polished point's scaled error
  // is within the tolerance, the iterate and info become its, the iterate
  // before it is kept as the solution's interior one
  // (interior_point_iterate.hpp), and the result is true; otherwise both
  // stay, and r is measured again at the iterate.
  bool attempt(const InteriorPointSettings& settings, double iterate_error, NewtonVectors& r,
               NewtonVectors& candidate, InteriorPointSolution& iterate, InteriorPointInfo& info) {
    auto start = Clock::now();
    sharpen(kSharpening, iterate);
    InteriorPointInfo candidate_info = info;
    residuals_.measure<D>(iterate, r, candidate_info);
    newton_.assemble();
    info.assembly_seconds += seconds_since(start);
    start = Clock::now();
    const bool factored = newton_.factor();
    info.factorization_seconds += seconds_since(start);
    start = Clock::now();
    if (factored) {
      newton_.direction(r, {}, candidate, iterate_error);
      candidate.x += iterate.x;
      candidate.y += iterate.y;
    }
    sharpen(1.0 / kSharpening, iterate);
    bool polished = false;
    if (factored) {
      passes_.each([&](int k) { complete_group(k, iterate, candidate); });
      InteriorPointSolution trial;
      const auto exchange = [&]() {
        trial.x.swap(candidate.x);
        trial.y.swap(candidate.y);
        trial.w.swap(candidate.w);
        trial.z.swap(candidate.z);
      };
      exchange();
      const double gap = residuals_.measure<D>(trial, r, candidate_info);
      polished = residuals_.scaled_error(candidate_info, gap, settings.objective_floor, trial.x) <= settings.tolerance;
      if (polished) {
        std::swap(trial, iterate);
        iterate.interior = static_cast<const InteriorPointIterate&>(trial);
      }
      exchange();  // the direction's room back, whichever point it holds
    }
    info.solve_seconds += seconds_since(start);
    if (polished) {
      candidate_info.assembly_seconds = info.assembly_seconds;
      candidate_info.factorization_seconds = info.factorization_seconds;
      candidate_info.solve_seconds = info.solve_seconds;
      info = candidate_info;
      return true;
    }
    residuals_.measure<D>(iterate, r, info);
    return false;
  }

private:
  // Group k's slacks and multipliers at the polished forces and balance
  // multipliers in `point` (x, y), the rows taken active as at `iterate`.
  void complete_group(int k, const InteriorPointSolution& iterate, NewtonVectors& point) const {
    const ForceGroup& group = problem_.groups[k];
    const GroupRules& rules = problem_.rules_of(group);
    const int first = inequality_.first[k];
    const int rows = inequality_.first[k + 1] - first;
    const Eigen::Vector4d xk = point.x.template segment<4>(4 * k);
    // G_S^T z_S = count (H x + q) - A_k^T y: the dual residual's equation.
    const Eigen::Vector4d pull =
        twins_.count(k) * (rules.hessian.cwiseProduct(xk) + rules.linear) - group_reaction<D>(group, point.y);
    Eigen::Matrix<double, 4, Eigen::Dynamic, 0, 4, kMaxGroupRows> active(4, 0);
    for (int i = 0; i < rows; ++i) {
      if (!taken_active(iterate, first + i)) continue;
      active.conservativeResize(Eigen::NoChange, active.cols() + 1);
      active.col(active.cols() - 1) = rules.rows.row(i).transpose();
    }
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxGroupRows, 1> multipliers;
    if (active.cols() > 0) multipliers = active.completeOrthogonalDecomposition().solve(pull);
    GroupRowsVector slack = rules.rows * xk;
    subtract_lower_bound(problem_, k, slack);
    for (int i = 0, a = 0; i < rows; ++i) {
      const bool is_active = taken_active(iterate, first + i);
      point.w(first + i) = is_active ? kPolishedFloor : std::max(slack(i), kPolishedFloor);
      point.z(first + i) = is_active ? std::max(multipliers(a++), kPolishedFloor) : kPolishedFloor;
    }
  }

  const EquilibriumProblem& problem_;
  const InequalityRows& inequality_;
  const TwinGroups& twins_;
  GroupPasses& passes_;
  NewtonSystem<D>& newton_;
  IterateResiduals& residuals_;
};

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
  if (warm) twins_.merge_solution(starting_point(solution), first_row, merged);
  InteriorPointInfo info = solve_groups(twins_.merge(problem), settings, merged, warm);
  twins_.split_solution(merged, first_row, solution);
  if (merged.interior.x.size() > 0) twins_.split_solution(merged.interior, first_row, solution.interior);
  else solution.interior = {};
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
  if (!cold_start && &starting_point(solution) != &solution) {
    static_cast<InteriorPointIterate&>(solution) = std::move(solution.interior);
  }
  solution.interior = {};
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
  ActiveSetPolish<D> polish(problem, inequality, twins_, passes, newton, residuals);
  const int factorizations_before = normal_.factorizations();

  bool starting = cold_start;
  double polish_below = kPolishBelow;
  double last_separation = 0.0;  // the iterate's separation at the iteration before (ActiveSetPolish)
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

    if (!starting && error_now <= kSeparationFrom) {
      const double separation = ActiveSetPolish<D>::separation(solution);
      const bool separating = separation >= kPolishSeparation && separation >= kSeparationGrowth * last_separation;
      last_separation = separation;
      if (separating && error_now <= polish_below) {
        if (polish.attempt(settings, error_now, r, direction, solution, info)) {
          info.iterations = iteration + 1;
          info.status = SolverStatus::converged;
          break;
        }
        polish_below = kPolishProgress * error_now;
        start = Clock::now();
      }
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
