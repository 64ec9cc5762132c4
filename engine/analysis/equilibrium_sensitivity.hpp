// How the optimal penalty of the equilibrium QP changes with the data the
// geometry gives it: the envelope theorem (Shin 2014, "Analytic structural
// gradient"). At the optimum (x, y) of
//     P = min 1/2 x^T H x + q^T x   subject to   A x = b,  G x >= 0,
// with G fixed (friction rows live in each interface's own frame),
//     dP/dtheta = -y^T (dA/dtheta) x + y^T (db/dtheta),
// so the derivatives need no second factorisation. These are the partial
// derivatives with respect to each piece of problem data; the structural
// gradient chains them with how that data moves with the block vertices.
#pragma once

#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point.hpp"
#include "core/types.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct EquilibriumSensitivity {
  // Per contact vertex of the problem (the first contact_vertex_count groups):
  std::vector<Vec3> vertex_position;  // dP/d(position), 1/m
  std::vector<Mat3> vertex_frame;     // columns dP/d(normal), dP/d(u), dP/d(v) of its interface frame
  // Per block (structure order; zero for supports and blocks not analysed):
  std::vector<Vec3> block_centroid;   // dP/d(centroid), 1/m
  std::vector<double> block_weight;   // dP/d(weight), 1/N
  // Per cable (structure order): dP/d(end point), 1/m, through its direction,
  // its attachment arms and its own weight (not through the units).
  std::vector<Vec3> cable_from, cable_to;
  double weight_unit = 0.0;           // dP/d(problem.weight_unit), 1/N
  double length_unit = 0.0;           // dP/d(problem.length_unit), 1/m
};

// The solver's optimum for `problem`, built from `structure`: x (4 per
// group), y (problem.row_count) and z (the groups' rule rows).
EquilibriumSensitivity equilibrium_sensitivity(const Structure& structure,
                                               const EquilibriumProblem& problem,
                                               const InteriorPointSolution& optimum);

}  // namespace ashlar
