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
// unanalysed blocks stand still. `dual_unit`, when given, receives what one
// mechanism unit of a vertex's relative velocity along a contact force is
// in the program's dual units (the multipliers times the force's column):
// the rate, per scaled unit of that force, at which it changes the
// objective.
std::vector<BlockMotion> mechanism_of(const Structure& structure, const EquilibriumProblem& problem,
                                      const double* multipliers, double* dual_unit = nullptr);

// The block as the mechanism moves it, rigidly: turned about its centroid
// by scale x |rotation|, then shifted by scale x velocity (scale in m per
// mechanism unit: the fastest centroid moves scale metres).
Block moved_by_mechanism(const Block& block, const BlockMotion& motion, double scale);
// Point p of a block whose centroid is `centroid`, moved likewise.
Vec3 moved_point(const Vec3& p, const Vec3& centroid, const BlockMotion& motion, double scale);

// Interfaces whose vertices move apart in the mechanism: by more than 1e-6
// of the fastest relative motion anywhere and by more than `noise`
// (mechanism units: what the multipliers' accuracy leaves moving at joints
// that do not move; 0 for the exact multipliers of a simplex vertex).
// Opening and slip count towards the mode only above 1e-3 of the
// interface's own fastest vertex and above `noise` likewise.
std::vector<LimitInterface> limit_interfaces(const Structure& structure, const std::vector<Interface>& interfaces,
                                             const std::vector<BlockMotion>& motion, double noise = 0.0);

}  // namespace ashlar
