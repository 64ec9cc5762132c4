// Collapse mechanisms from the balance rows' multipliers of an equilibrium
// program (the load-factor LP's duals, the analysis QP's y): the blocks'
// virtual motions and how each interface moves in them.
#pragma once

#include <vector>

#include "core/enum_names.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "core/types.hpp"
#include "structure/structure.hpp"

namespace ashlar {

// How an interface moves in the collapse mechanism.
enum class LimitMode {
  hinge,          // rotates open about an edge or a corner, no slip
  sliding,        // slips (opening only as much as associative friction dilates)
  hinge_sliding,  // both
  separation,     // lifts off as a whole
};
inline constexpr EnumNames<LimitMode, 4> kLimitModeNames{{{{LimitMode::hinge, "hinge"},
                                                           {LimitMode::sliding, "sliding"},
                                                           {LimitMode::hinge_sliding, "hinge_sliding"},
                                                           {LimitMode::separation, "separation"}}}};

struct LimitInterface {
  int interface = -1;          // index into Structure::interfaces(options.contact)
  LimitMode mode = LimitMode::hinge;
  // m: mean of the contact vertices that do not open (the hinge's edge or
  // corner); the interface centre when every vertex moves.
  Vec3 pivot = Vec3::Zero();
  double opening = 0.0;        // largest normal separation rate of a vertex (mechanism units)
  double slip = 0.0;           // largest tangential slip rate of a vertex
};

// A block's rigid motion in the collapse mechanism, about its centroid.
// Scaled so that the fastest centroid moves at 1 (a rotation-only
// mechanism: the fastest vertex); only the shape is meaningful.
struct BlockMotion {
  Vec3 velocity = Vec3::Zero();  // of the centroid
  Vec3 rotation = Vec3::Zero();  // rad per unit
};

// The blocks' virtual motions from the multipliers of the balance rows
// (problem.row_count of them, scaled as the problem): with their sign
// negated, the direction in which the loads do positive work. Supports and
// unanalysed blocks stand still.
std::vector<BlockMotion> mechanism_of(const Structure& structure, const EquilibriumProblem& problem,
                                      const double* multipliers);

// Interfaces whose vertices move apart in the mechanism, relative to the
// fastest relative motion anywhere (smaller is numerical noise).
std::vector<LimitInterface> limit_interfaces(const Structure& structure, const std::vector<Interface>& interfaces,
                                             const std::vector<BlockMotion>& motion);

}  // namespace ashlar
