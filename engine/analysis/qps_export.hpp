// The equilibrium QP in QPS form (free MPS with a QUADOBJ section), so any
// QP solver can solve exactly what ashlar solves.
#pragma once

#include <string>

#include "analysis/equilibrium_problem.hpp"

namespace ashlar {

// The problem's scaled QP: minimise 1/2 x^T H x + q^T x subject to the
// balance rows (E), the per-vertex inequality rows other than the bounds
// (G, >= 0), c >= 0, s >= 0 (bounds) and f_u, f_v free. Its optimal value
// equals EquilibriumResult::objective. Rows and columns are named after the
// blocks, interfaces and vertices they belong to.
std::string equilibrium_qps(const EquilibriumProblem& problem, const std::string& name);

// Writes equilibrium_qps() atomically; throws IoError naming the path.
void write_equilibrium_qps(const EquilibriumProblem& problem, const std::string& path);

}  // namespace ashlar
