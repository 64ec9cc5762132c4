// Load traces (Shin 2014, "Force flow", figure 10): where one block's weight
// goes on its way to the ground.
//
// The block's weight is split into `traces` equal downward forces, each at
// the block's centroid or at a random point inside it. A trace at point p on
// block B with direction d asks how the contact forces respond to a force d
// at p on B (eq. 7: the optimum's active set held). The contact vertices of
// B where B then presses harder into a neighbour carry the load on; the
// trace jumps to a random point of B's interfaces, with a density
// interpolated linearly over each contact polygon from those vertices'
// outgoing force magnitudes, and continues into that neighbour along the
// resultant of what B passes to it there. It ends on a support's interface,
// or is lost after max_steps or on a block that passes nothing on. Every
// random draw is made from std::mt19937_64's raw output, so a seed gives the
// same traces with any standard library.
//
// Only contact forces carry traces: a block that hands its load on through
// cables alone loses the trace there.
#pragma once

#include <cstdint>
#include <vector>

#include "core/enum_names.hpp"
#include "analysis/equilibrium.hpp"

namespace ashlar {

enum class TraceStart {
  centroid,  // every trace starts at the block's centroid (figure 10a)
  random,    // each at its own point, uniform in the block's volume (figure 10b)
};
inline constexpr EnumNames<TraceStart, 2> kTraceStartNames{
    {{{TraceStart::centroid, "centroid"}, {TraceStart::random, "random"}}}};

struct ForceFlowOptions {
  int traces = 200;          // >= 1; each carries the block's weight / traces
  std::uint64_t seed = 1;    // of the std::mt19937_64 behind every random draw
  TraceStart start = TraceStart::centroid;
  int max_steps = 0;         // interfaces crossed per trace before it counts as lost; 0: 4 x blocks
  // Whether a trace may leave a block through the interface it came in by.
  // The trace's force, gathered at one point of that interface, turns the
  // block, and part of the answer is a couple across the same interface:
  // allowed, some traces go back (an eighth of those entering an H frame's
  // post turn back into its beam; an arch's traces wander to and fro, and
  // many are lost). Not allowed (the default), every trace moves on and the
  // shares follow the statics (a beam's reactions).
  bool turn_back = false;
};

// The share of the traced weight that reaches one support interface.
struct SupportShare {
  int interface = -1;  // 0-based index into Structure::interfaces(settings.problem.contact)
  int a = -1, b = -1;  // its blocks, 0-based
  double share = 0.0;  // traces that ended there / traces
};

struct ForceFlow {
  // Per trace, in metres: the start point, then the point of every interface
  // it crossed; the last lies on a support interface unless the trace was
  // lost. Empty when not `valid`.
  std::vector<std::vector<Vec3>> polylines;
  // Per trace: the support interface it reached (0-based), or -1 when lost.
  std::vector<int> support_interface;
  std::vector<SupportShare> shares;  // one per support interface reached, by interface
  int lost = 0;                      // traces that reached no support
  // The analysis whose response the traces follow. When it is not stable
  // the traces still follow its best (tension-carrying) equilibrium.
  EquilibriumResult analysis;
  bool stable = false;               // analysis.stable
  // False when the analysis failed (numerical_error) or its active-set
  // system could not be factorised: then no trace moved and all are lost.
  bool valid = false;
  double seconds = 0.0;  // the whole call, analysis included
};

// Traces the weight of free block `block` (0-based). Throws InvalidArgument
// when the block is out of range, a support or not analysed (no chain of
// contacts to a support), or when traces < 1 or max_steps < 0.
ForceFlow trace_loads(const Structure& structure, int block, const ForceFlowOptions& options,
                      const AnalysisSettings& settings);

// The change of `block`'s balance rows' right-hand side (problem.block_rows
// entries, scaled as problem.rhs) when a force `force` (N) acts on it at
// `at` (m): exactly what build_equilibrium_problem adds for a PointLoad.
Eigen::VectorXd point_force_rows(const EquilibriumProblem& problem, const Structure& structure,
                                 int block, const Vec3& force, const Vec3& at);

// True when `point` (m) lies inside the closed polyhedron `block` (convex or
// not): its winding number, from the solid angles of the fan-triangulated
// faces, is 1 rather than 0. Points on the surface may go either way.
bool contains_point(const Block& block, const Vec3& point);

}  // namespace ashlar
