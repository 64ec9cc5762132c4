// Rigid-block equilibrium analysis: is there a compression-only equilibrium
// that respects friction, and if not, how much tension does the best one need?
#pragma once

#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "analysis/cra_settings.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point.hpp"
#include "analysis/mechanism.hpp"

namespace ashlar {

// Which question the analysis answers (see docs/api.md, "Two methods").
enum class AnalysisMethod {
  // Is there a compression-only equilibrium within the friction cones (the
  // lower-bound theorem, Shin 2014 eq. 1)? Exact for associative friction;
  // with real, non-dilatant joints its "stable" can rest on normal forces
  // nothing creates (a block clamped between walls).
  equilibrium,
  // Is there one whose friction needs no more normal force than the joints
  // develop from an unstressed state (kinematic.hpp)?
  kinematic,
  // Coupled rigid-block analysis (Kao et al. 2022, cra.hpp): a
  // compression-only equilibrium within the friction cones together with a
  // compatible virtual displacement of the blocks, whose sliding the
  // friction opposes; a nonlinear program solved by IPOPT.
  cra,
  // Its penalty form: tension allowed at a high quadratic cost, so that an
  // unstable structure still has an answer (the tension it needs and how it
  // would move).
  cra_penalty,
};

struct AnalysisSettings {
  AnalysisMethod method = AnalysisMethod::equilibrium;
  EquilibriumOptions problem;
  InteriorPointSettings solver;
  // A structure is stable when the solver's forces, with every tension
  // dropped, balance each block to this fraction of its own load (weight
  // plus point loads, or the mean block weight when larger; moments over the
  // block's size) and break no compression or friction bound by more than
  // this fraction of the mean block weight.
  double stable_tolerance = 1e-6;
  // Stop as soon as forces without tension are proven to balance (status
  // certified): the verdict "stable" without the optimum, so the forces are
  // a compression-only equilibrium but not the most even one, and
  // penalty / objective are theirs. Unstable structures still solve to the
  // optimum, whose tension is what proves them unstable.
  bool verdict_only = false;
  // Kinematic method: at most this many equilibrium solves (rounds) to
  // settle the joints' shear strengths, which settle when no vertex's
  // changes by more than round_tolerance of the mean block weight.
  int max_rounds = 200;
  double round_tolerance = 1e-5;
  // Methods cra and cra_penalty (cra_settings.hpp).
  CraSettings cra;
};

// A block's small virtual displacement (methods cra and cra_penalty):
// the translation of its centroid (m) and its rotation about it (rad).
struct BlockDisplacement {
  Vec3 translation = Vec3::Zero();
  Vec3 rotation = Vec3::Zero();
};

// A verdict is borderline when imbalance_without_tension lies between these
// multiples of stable_tolerance (1e-9 to 1e-5 by default): a stable verdict
// whose forces still needed tension far above the solver's noise (about
// 1e-11 for a structure that stands with room to spare), or an unstable one
// within the accuracy of an inaccurate solve (about 1e-5).
constexpr double kBorderlineBelow = 1e-3;
constexpr double kBorderlineAbove = 10.0;

// Forces through one interface, acting on block b from block a (N, m).
struct InterfaceForces {
  int a = -1, b = -1;
  double normal_force = 0.0;  // compression minus tension, positive in compression
  double compression = 0.0;   // sum of vertex compressions
  double tension = 0.0;       // sum of vertex tensions
  Vec3 resultant = Vec3::Zero();
  // Point of the interface plane where the resultant's normal part acts;
  // meaningful when normal_force > 0 (else the interface centre).
  Vec3 center_of_pressure = Vec3::Zero();
};

// A cable's axial force (N).
struct CableForces {
  double tension = 0.0;      // positive in tension; negative when the best equilibrium pushes
  double compression = 0.0;  // the penalised compressive part (>= 0)
};

struct AnalysisTimings {
  double setup = 0.0;          // contact detection, problem and pattern analysis
  double assembly = 0.0;       // per-iteration residuals and normal-matrix values
  double factorization = 0.0;  // CHOLMOD numeric factorisations
  double solve = 0.0;          // triangular solves and updates
};

struct EquilibriumResult {
  AnalysisMethod method = AnalysisMethod::equilibrium;
  bool stable = false;
  // Total tension of the best equilibrium over the total weight
  // (dimensionless): interface tension, cable compression, and virtual
  // torques over the unit of length; exactly 0 when stable. Infinite when a
  // free block has no chain of contacts to a support, or when the solver
  // failed (numerical_error); approximate after max_iterations.
  double infeasibility = 0.0;
  // The QP's optimal value per analysed body, in units of the mean weight:
  // the thesis's infeasibility measure (Shin 2014 eq. 1, after Whiting), the
  // smooth function that gradients differentiate and the optimiser lowers.
  // It follows infeasibility closely when unstable; when stable only the
  // tiny force regularisation is left (about force_weight / 2 per body).
  double penalty = 0.0;
  double objective = 0.0;      // the QP's optimum, scaled as in the QPS export
  SolverStatus status = SolverStatus::numerical_error;
  int iterations = 0;
  int factorizations = 0;
  double seconds = 0.0;        // wall time of the whole analysis
  AnalysisTimings timings;
  // Distance of the forces, tension dropped, from a compression-only
  // equilibrium (see AnalysisSettings::stable_tolerance), which it is
  // compared with.
  double imbalance_without_tension = 0.0;
  // The verdict is at the resolution of the analysis: the imbalance lies in
  // (kBorderlineBelow, kBorderlineAbove] x stable_tolerance. A stable
  // verdict then rests on forces that still needed some tension (the
  // structure may be unstable by less than the tolerance, e.g. a block past
  // its support's edge by 1e-7 of its width); an unstable one on so little
  // tension that a less accurate solve could reverse it. Never for floating
  // blocks.
  bool borderline = false;
  std::vector<int> floating_blocks;        // 0-based; they make the structure unstable
  // Why each floating block floats (parallel to floating_blocks): the
  // nearest block it has no interface with, within 1 % of the structure's
  // size, and the contact tolerance that would give them one.
  std::vector<MissedContact> floating_gaps;
  std::vector<Eigen::Vector4d> vertex_forces;  // (c, s, f_u, f_v) in N per contact vertex
  std::vector<Vec3> vertex_positions;          // m
  std::vector<int> vertex_interface;           // interface index of each vertex
  std::vector<InterfaceForces> interfaces;     // parallel to Structure::interfaces()
  std::vector<double> block_tension;           // N: tension over each block's interfaces
  std::vector<CableForces> cables;             // parallel to Structure::cables()
  std::vector<Vec3> virtual_torques;           // N m per block, about its centroid
  // How an unstable structure starts to move: per block (supports and
  // floating blocks still), the virtual motion that the best equilibrium's
  // balance multipliers give (mechanism.hpp): the direction in which the
  // loads make the penalised tension grow. With it, the interfaces that
  // move and how. Empty when stable, floating or without an answer.
  std::vector<BlockMotion> mechanism;
  std::vector<LimitInterface> limit;
  // Kinematic method: equilibrium solves until the joints' strengths
  // settled (1 for the equilibrium method).
  int rounds = 1;
  // Methods cra and cra_penalty: per block (zero for supports and blocks
  // not analysed) the virtual displacement of the solution. Empty for the
  // other methods and when the solve gave no answer.
  std::vector<BlockDisplacement> displacements;
  // An unstable verdict without floating blocks: the blocks whose balance
  // needs the most tension (over 1e-3 of the largest, at most
  // kFailingBlocksShown, most first), and parallel to them the contact each
  // just misses, as floating_gaps: a verdict that turns on a joint the
  // contact tolerance did not find. Filled by analyze_equilibrium.
  std::vector<int> failing_blocks;
  std::vector<MissedContact> failing_gaps;
  // What a user should know before trusting the verdict (verdict_notes.hpp),
  // e.g. a stable verdict that rests on friction at its limit.
  std::vector<std::string> warnings;
  InteriorPointSolution solution;              // scaled; for warm starts (filled by analyze_equilibrium)
};

inline constexpr EnumNames<AnalysisMethod, 4> kAnalysisMethodNames{{{{AnalysisMethod::equilibrium, "equilibrium"},
                                                                    {AnalysisMethod::kinematic, "kinematic"},
                                                                    {AnalysisMethod::cra, "cra"},
                                                                    {AnalysisMethod::cra_penalty, "cra_penalty"}}}};

// What a method says about a structure. `settles` is the dynamics'
// (compare_methods.hpp): some block moved further than
// SimulationOptions::moved_fraction of its size before everything came to
// rest (settle_speed): it stands, but not where it was drawn.
enum class Verdict { stands, falls, settles, no_verdict };
inline constexpr EnumNames<Verdict, 4> kVerdictNames{{{{Verdict::stands, "stands"},
                                                       {Verdict::falls, "falls"},
                                                       {Verdict::settles, "settles"},
                                                       {Verdict::no_verdict, "no verdict"}}}};

// What one analysis says: stands, falls (a converged unstable answer, or
// floating blocks) or no verdict (not converged, interrupted).
Verdict verdict_of(const EquilibriumResult& result);

// Whether `method` is one of the coupled rigid-block analyses.
inline bool is_cra(AnalysisMethod method) {
  return method == AnalysisMethod::cra || method == AnalysisMethod::cra_penalty;
}

// Runs the analysis (the method of `settings`). Throws InvalidArgument for bad settings; every outcome
// (unstable, not converged, floating blocks) is reported in the result.
// `warm_start`, if given, must come from the same structure. `problem`, if
// given, receives the QP that was solved (for its derivatives). One
// EquilibriumAnalysis (equilibrium_analysis.hpp) set up and solved once;
// keep that object instead to solve the same pattern again.
EquilibriumResult analyze_equilibrium(const Structure& structure, const AnalysisSettings& settings,
                                      const EquilibriumResult* warm_start = nullptr,
                                      EquilibriumProblem* problem = nullptr);

// Throws InvalidArgument, naming the setting, unless the solver settings
// and stable_tolerance are in range.
void check_analysis_settings(const AnalysisSettings& settings);

// Throws InvalidArgument unless `block` (0-based) is a free block of the
// structure: in range and not a support. `caller`, when not empty, begins
// the message ("caller: block ...").
void check_free_block(const Structure& structure, int block, const std::string& caller);
// Throws InvalidArgument (message as check_free_block's) unless `block`
// has balance rows in `problem`: some path of contacts leads to a support.
void check_analysed_block(const EquilibriumProblem& problem, const Structure& structure, int block,
                          const std::string& caller);

// The blocks a per-block analysis is asked about (load capacity, important
// weights), as a mask over the structure's blocks: `blocks` (0-based), or
// every block when it is empty. Throws InvalidArgument, naming `caller` and
// the entry, for a block out of range or listed twice.
std::vector<char> asked_blocks(const Structure& structure, const std::vector<int>& blocks, const std::string& caller);

// The line of thrust as polylines (m) to draw: a segment joins the centres
// of pressure of every two compressed interfaces of one free block, and
// segments are joined end to end through blocks with two such interfaces.
// For a chain of blocks (an arch, a column) that is one polyline through the
// points of thrust_line(structure, result), in their order or the reverse;
// where a block has three or more (a pier under a flyer and a pinnacle) the
// line branches there. An interface in compression with no other on its
// blocks is a polyline of one point. Interfaces whose normal force is under
// 1e-3 of the largest (round-off, blocks that merely touch) are left out.
// `result` must be an analysis of `structure`.
std::vector<std::vector<Vec3>> thrust_polylines(const Structure& structure,
                                                const EquilibriumResult& result);

// The longest of thrust_polylines: for a chain of blocks (an arch, a column)
// the whole line, from the end at a support when one end is; for a branching
// structure its longest branch (thrust_polylines gives every branch).
std::vector<Vec3> thrust_line(const Structure& structure, const EquilibriumResult& result);

}  // namespace ashlar
