#include "analysis/weight_analysis.hpp"

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <string>

#include "analysis/equilibrium_analysis.hpp"
#include "analysis/problem_symmetry.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_loop.hpp"

namespace ashlar {

namespace {

// How much more eq. 8's least squares weigh than the analysis's
// regularisation (force_weight / bodies, 1e-4 / n by default): its
// quadratic is eq. 8's whole objective, and at the analysis's weight it is
// so flat beside the tension penalty that the interior point spends most of
// its iterations on it after the tension is gone. At 1 / n the penalty
// stays exact by the analysis's own argument (the regularisation's pull on
// the multipliers, of the forces' size, stays below the tension's price):
// the 16 x 18 dome's important weights took 5,300 iterations instead of
// 6,030, at the same accuracy. A weight of 0.1 / n took 5,557, 3 / n 5,152
// and 9 / n 5,028: the heavier the fewer, and the nearer that bound.
constexpr double kLeastSquaresWeight = 1e4;

// The objective the duality gap of eq. 8's problem is measured against
// (InteriorPointSettings::objective_floor), scaled: its own, down to this.
// The analysis measures the gap against 1 + |objective|, a unit that the
// necessary-weights objective never reaches (1e-4 to 1e-2 on walls, domes
// and vaults), so that the tolerance was on the gap alone, which left the
// weights as far off as the objective is small: against answers at a
// tolerance 1e4 times finer, the important weights of a planar 431-block
// wall were off by 0.20 of the largest, the 16 x 18 dome's by 2.2e-3, a
// 16 x 8 vault's by 3.2e-3. Relative to the objective itself: 6.8e-4,
// 4.4e-5 and 2.1e-5, for 30 % more time on the dome (14.2 s -> 18.6 s on
// one core). The floor only keeps a vanishing objective from asking for
// no gap at all; the smallest seen is 1e-4.
constexpr double kObjectiveFloor = 1e-9;

// The analysis's settings with eq. 8's least squares weighted up. The
// solver's tolerance bounds the duality gap, whose share of the objective
// fixes the weights' accuracy: scaled with the objective, it means the
// same share as the analysis's.
AnalysisSettings least_squares_settings(AnalysisSettings settings) {
  settings.problem.force_weight *= kLeastSquaresWeight;
  settings.solver.tolerance *= kLeastSquaresWeight;
  settings.solver.objective_floor = kObjectiveFloor;
  return settings;
}

// The necessary-weights problem of eq. 8 for every choice of the block
// that keeps its weight: the free blocks' weights leave the right-hand side
// and become unknowns w_j >= 0 (one group each, acting on its block's
// vertical row only, so the normal matrix's pattern is unchanged and one
// symbolic analysis serves every choice). The chosen block's weight goes
// back into the right-hand side and its unknown is cut off.
class NecessaryWeightsProblem {
public:
  NecessaryWeightsProblem(const Structure& structure, const AnalysisSettings& settings,
                          SolverCores cores = SolverCores::all)
      : structure_(structure), settings_(least_squares_settings(settings)) {
    check_analysis_settings(settings);  // the caller's, before they are scaled
    EquilibriumProblem problem = build_equilibrium_problem(structure, settings_.problem);
    vertical_ = problem.vertical_row();
    const double wu = problem.weight_unit;
    group_of_block_.assign(structure.size(), -1);
    for (int j = 0; j < structure.size(); ++j) {
      const int row = problem.row_of_block[j];
      if (row < 0) continue;
      problem.rhs(row + vertical_) -= structure.block(j).mass() * kGravity / wu;
      ForceGroup weight;
      weight.kind = GroupKind::weight;
      weight.source = j;
      weight.block_a = j;
      weight.row_a = row;
      weight.set_alone_on_a(vertical_, 0, -1.0);  // the weight joins the loads the contacts carry
      group_of_block_[j] = static_cast<int>(problem.groups.size());
      problem.groups.push_back(weight);
    }
    rhs_without_weights_ = problem.rhs;
    analysis_ = std::make_unique<EquilibriumAnalysis>(std::move(problem), settings_, cores);
  }

  const EquilibriumProblem& problem() const { return analysis_->problem(); }

  NecessaryWeights solve(int block, bool warm_start) {
    const auto start = Clock::now();
    const EquilibriumProblem& problem = analysis_->problem();
    check_analysed_block(problem, structure_, block, "");
    const double wu = problem.weight_unit;
    const double own_weight = structure_.block(block).mass() * kGravity;
    // The weight unknowns' effects: the last chosen block's back, this
    // one's cut off; its weight back in the right-hand side.
    if (chosen_ >= 0) set_weight_effect(chosen_, -1.0);
    chosen_ = block;
    set_weight_effect(block, 0.0);
    Eigen::VectorXd rhs = rhs_without_weights_;
    rhs(problem.row_of_block[block] + vertical_) += own_weight / wu;
    analysis_->set_rhs(std::move(rhs));

    const InteriorPointInfo info = analysis_->solve_qp(settings_.solver, warm_start);
    const InteriorPointSolution& solution = analysis_->solution();
    NecessaryWeights result;
    result.status = info.status;
    result.iterations = info.iterations;
    result.weights.assign(structure_.size(), 0.0);
    double penalised = 0.0;
    for (size_t k = 0; k < problem.groups.size(); ++k) {
      const ForceGroup& group = problem.groups[k];
      const Eigen::Vector4d x = solution.x.segment<4>(4 * static_cast<Eigen::Index>(k));
      penalised += problem.rules_of(group).linear.dot(x);
      if (group.kind == GroupKind::weight && group.source != block) {
        result.weights[group.source] = x(0) * wu;
      }
    }
    result.weights[block] = own_weight;
    const bool floating = problem.has_floating_bodies();
    result.stable = !floating && !has_no_answer(info.status) &&
                    compression_only_imbalance(problem, solution.x) <= settings_.stable_tolerance;
    if (floating || has_no_answer(info.status)) {
      result.infeasibility = std::numeric_limits<double>::infinity();
    } else {
      result.infeasibility = result.stable ? 0.0 : penalised / std::max(problem.body_count, 1);
    }
    result.seconds = seconds_since(start);
    return result;
  }

private:
  // Block j's weight unknown enters its vertical row with `effect` (-1:
  // carried by the contacts; 0: cut off).
  void set_weight_effect(int j, double effect) {
    const int k = group_of_block_[j];
    ForceGroup group = analysis_->problem().groups[k];
    group.set_alone_on_a(vertical_, 0, effect);
    analysis_->set_group(k, group);
  }

  const Structure& structure_;
  const AnalysisSettings settings_;
  int vertical_ = 2;
  std::vector<int> group_of_block_;  // the weight group of each analysed block, else -1
  Eigen::VectorXd rhs_without_weights_;
  std::unique_ptr<EquilibriumAnalysis> analysis_;  // of eq. 8's problem, with the weights' groups
  int chosen_ = -1;
};

}  // namespace

WeightSensitivity weight_sensitivity(const Structure& structure, int block,
                                     const AnalysisSettings& settings) {
  check_free_block(structure, block, "");
  WeightSensitivity result;
  EquilibriumAnalysis analysis(structure, settings);
  result.analysis = analysis.solve();
  const EquilibriumProblem& problem = analysis.problem();
  check_analysed_block(problem, structure, block, "");
  const auto start = Clock::now();
  // The response reuses the analysis's factorisation pattern.
  if (!analysis.prepare_response()) return result;
  const EquilibriumSolver& solver = analysis.solver();

  // One newton more on the block is 1 / weight_unit on its vertical row;
  // the scaled force change is then in weight units per weight unit: N/N.
  Eigen::VectorXd more_weight = Eigen::VectorXd::Zero(problem.row_count);
  more_weight(problem.row_of_block[block] + problem.vertical_row()) = 1.0;
  const Eigen::VectorXd multipliers = solver.multiplier_response(more_weight);

  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(settings.problem.contact);

  const std::vector<Interface>& interfaces = *interfaces_list;
  result.interface_change.assign(interfaces.size(), 0.0);
  result.interface_resultant_change.assign(interfaces.size(), Vec3::Zero());
  result.block_change.assign(structure.size(), 0.0);
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const ForceGroup& vertex = problem.groups[k];
    const Interface& contact = interfaces[vertex.source];
    const Eigen::Vector4d dx = solver.group_response(problem, k, multipliers);
    const Vec3 change = (dx(0) - dx(1)) * contact.normal + dx(2) * contact.u + dx(3) * contact.v;
    result.interface_change[vertex.source] += change.norm();
    result.interface_resultant_change[vertex.source] += change;
  }
  for (size_t i = 0; i < interfaces.size(); ++i) {
    result.block_change[interfaces[i].a] += result.interface_change[i];
    result.block_change[interfaces[i].b] += result.interface_change[i];
  }
  result.valid = true;
  result.seconds = seconds_since(start);
  return result;
}

NecessaryWeights necessary_weights(const Structure& structure, int block,
                                   const AnalysisSettings& settings) {
  check_free_block(structure, block, "");
  NecessaryWeightsProblem problem(structure, settings);
  return problem.solve(block, false);
}

ImportantWeights important_weights(const Structure& structure, const ImportantWeightsSettings& weights_settings,
                                   const ProgressCount& progress) {
  const auto start = Clock::now();
  const AnalysisSettings& settings = weights_settings.analysis;
  const int threads = weights_settings.threads;
  const bool use_symmetry = weights_settings.use_symmetry;
  check_analysis_settings(settings);
  const std::vector<char> asked = asked_blocks(structure, weights_settings.blocks, "important weights");
  // Each problem's solver on one core when the workers may be several.
  const SolverCores cores =
      worker_count(threads, std::numeric_limits<int>::max()) > 1 ? SolverCores::one : SolverCores::all;
  // The calling thread's problem, set up here: it tells which blocks are
  // analysed, and throws for a structure the analysis refuses.
  auto first_problem = std::make_unique<NecessaryWeightsProblem>(structure, settings, cores);
  // Eq. 8's optimum is unique (its objective is strictly convex), so the
  // necessary weights for a block's image under a symmetry of the problem
  // are the image of the block's own: one block of each orbit is solved.
  const ProblemSymmetry symmetry = find_problem_symmetry(structure, first_problem->problem(), use_symmetry);
  // Per block solved: the symmetries that map it to the blocks asked in its orbit.
  std::vector<std::vector<int>> orbit_of(structure.size());
  for (int i = 0; i < structure.size(); ++i) {
    if (first_problem->problem().row_of_block[i] < 0 || !asked[i]) continue;
    orbit_of[symmetry.representative[i]].push_back(symmetry.symmetry_of[i]);
  }
  std::vector<int> blocks;  // the free blocks solved, in block order
  for (int i = 0; i < structure.size(); ++i) {
    if (!orbit_of[i].empty()) blocks.push_back(i);
  }
  // Each worker takes a contiguous share of the blocks, in order, on a
  // problem and solver of its own, each solve warm from its own last one:
  // the shares, and so the sums, do not depend on timing.
  const int workers = worker_count(threads, static_cast<int>(blocks.size()));
  struct Share {
    std::vector<double> per_weight;  // N per block, summed over the share's blocks
    std::vector<int> unstable;
    int solves = 0, iterations = 0;
    bool interrupted = false;
  };
  std::vector<Share> shares(workers);
  std::atomic<int> done{0};
  const int total = static_cast<int>(blocks.size());
  auto work = [&](int w) {
    Share& share = shares[w];
    share.per_weight.assign(structure.size(), 0.0);
    const std::unique_ptr<NecessaryWeightsProblem> own =
        w == 0 ? std::move(first_problem) : std::make_unique<NecessaryWeightsProblem>(structure, settings, cores);
    NecessaryWeightsProblem& problem = *own;
    const size_t first = blocks.size() * w / workers, last = blocks.size() * (w + 1) / workers;
    for (size_t k = first; k < last; ++k) {
      const int i = blocks[k];
      const NecessaryWeights needed = problem.solve(i, share.solves > 0);
      if (needed.status == SolverStatus::interrupted) {
        share.interrupted = true;
        return;
      }
      ++share.solves;
      share.iterations += needed.iterations;
      const int now = ++done;
      if (w == 0 && progress) progress(now, total);  // on the calling thread
      for (const int e : orbit_of[i]) {
        const std::vector<int>& image = symmetry.block_maps[e];
        if (!needed.stable) share.unstable.push_back(image[i]);
        for (int j = 0; j < structure.size(); ++j) {
          if (j != i && image[j] >= 0) share.per_weight[image[j]] += needed.weights[j];
        }
      }
    }
  };
  if (progress) progress(0, total);
  ParallelLoop(workers, 1).run_parts(workers, work);  // worker 0 on this thread
  if (progress) progress(done, total);

  ImportantWeights result;
  result.per_volume.assign(structure.size(), 0.0);
  for (const Share& share : shares) {
    for (int j = 0; j < structure.size(); ++j) result.per_volume[j] += share.per_weight[j];
    result.unstable_blocks.insert(result.unstable_blocks.end(), share.unstable.begin(), share.unstable.end());
    result.solves += share.solves;
    result.iterations += share.iterations;
    if (share.interrupted) result.status = ImportantWeightsStatus::interrupted;
  }
  result.symmetries = static_cast<int>(symmetry.block_maps.size());
  std::sort(result.unstable_blocks.begin(), result.unstable_blocks.end());
  for (int j = 0; j < structure.size(); ++j) {
    if (result.per_volume[j] != 0.0) result.per_volume[j] /= structure.block(j).volume();
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace ashlar
