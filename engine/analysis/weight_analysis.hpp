// How the blocks' weights hold a structure up (Shin 2014, chapter 4): how
// the forces respond to one block's weight (eq. 7, figure 4), and which
// weights the other blocks need for one block to stand (eq. 8, figures 8, 9).
#pragma once

#include <vector>

#include "analysis/equilibrium.hpp"
#include "analysis/load_capacity.hpp"
#include "core/enum_names.hpp"

namespace ashlar {

struct WeightSensitivity {
  EquilibriumResult analysis;  // of the structure as it is; its active set is held
  // d(force)/d(weight of the chosen block), dimensionless (N per N), with
  // the optimum's active set held: per interface, the sum over its contact
  // vertices of the change of each vertex force's magnitude |dF_k|, and
  // the change of its resultant (acting on block b); per block, the sum
  // over the interfaces it touches. Empty when `valid` is false.
  std::vector<double> interface_change;
  std::vector<Vec3> interface_resultant_change;
  std::vector<double> block_change;
  // False when the analysis failed (numerical_error, floating blocks) or
  // its active-set system could not be factorised.
  bool valid = false;
  double seconds = 0.0;  // the sensitivity's own time, after the analysis
};

// Throws InvalidArgument when `block` (0-based) is out of range, a
// support, or not analysed (floating).
WeightSensitivity weight_sensitivity(const Structure& structure, int block,
                                     const AnalysisSettings& settings);

struct NecessaryWeights {
  // N per block: the chosen block's own weight; for the other free blocks
  // the least weights (in the least-squares sense of eq. 8, forces and
  // weights together) with which a compression-only equilibrium exists;
  // 0 for supports and floating blocks.
  std::vector<double> weights;
  // Whether those weights let the structure stand (no tension left, to
  // AnalysisSettings::stable_tolerance); when not, infeasibility is the
  // tension still needed over the total weight.
  bool stable = false;
  double infeasibility = 0.0;
  SolverStatus status = SolverStatus::numerical_error;
  int iterations = 0;
  double seconds = 0.0;
};

// Block `block` keeps its weight, every other free block's weight becomes
// an unknown w_j >= 0 (eq. 8). Throws InvalidArgument as weight_sensitivity.
NecessaryWeights necessary_weights(const Structure& structure, int block,
                                   const AnalysisSettings& settings);

struct ImportantWeightsSettings {
  AnalysisSettings analysis;  // friction, contacts, and the equilibrium solver's settings
  // Worker threads, 0 for one per hardware thread; each takes a contiguous
  // share of the blocks (its own problem, each solve warm from its own
  // last), so the answer depends on the count only to the solver's
  // tolerance.
  int threads = 0;
  // Solve one block per orbit of the problem's symmetries and map its
  // weights to the others (false: every block, for checking them).
  bool use_symmetry = true;
  // The free blocks i whose necessary weights are summed (0-based), or
  // every free block when empty: on a model without symmetry the cost is
  // per block asked.
  std::vector<int> blocks{};
};

// Whether every free block's problem was solved.
enum class ImportantWeightsStatus {
  done,
  interrupted,  // Ctrl-C or a sandbox deadline
};
inline constexpr EnumNames<ImportantWeightsStatus, 2> kImportantWeightsStatusNames{
    {{{ImportantWeightsStatus::done, "done"}, {ImportantWeightsStatus::interrupted, "interrupted"}}}};

struct ImportantWeights {
  // N/m^3 per block: the sum over every free block i (every one asked,
  // ImportantWeightsSettings::blocks) of block j's necessary weight for i
  // (i's own weight excluded), over block j's volume; 0 for supports and
  // floating blocks (figure 9).
  std::vector<double> per_volume;
  // Free blocks whose necessary-weights problem has no compression-only
  // solution (0-based); they add what they found all the same.
  std::vector<int> unstable_blocks;
  // done, or interrupted: per_volume then sums only the orbits of the
  // `solves` blocks done before.
  ImportantWeightsStatus status = ImportantWeightsStatus::done;
  int solves = 0;  // problems solved: one per orbit of the symmetries
  int iterations = 0;  // interior-point iterations over all of them (machine-independent cost)
  // The problem's symmetries used (analysis/problem_symmetry.hpp; 1: none,
  // or not searched).
  int symmetries = 1;
  double seconds = 0.0;
};

// One necessary-weights problem per free block asked, on one
// factorisation pattern, each warm-started from the last. Throws
// InvalidArgument as load_capacity. progress: as load_capacity's
// (analysis/load_capacity.hpp).
ImportantWeights important_weights(const Structure& structure, const ImportantWeightsSettings& settings,
                                   const ProgressCount& progress = {});

}  // namespace ashlar
