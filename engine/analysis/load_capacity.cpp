#include "analysis/load_capacity.hpp"

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <chrono>
#include <cmath>
#include <limits>

namespace ashlar {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The equilibrium QP's constraints without its penalised unknowns (tension,
// cable compression, virtual torques), as a linear program in Clp's form;
// one more column per analysed block: the multiple of its weight, fixed at 1.
struct EquilibriumProgram {
  std::vector<int> row_index, column_index;
  std::vector<double> value;
  std::vector<double> column_lower, column_upper, row_lower, row_upper;
  std::vector<int> multiplier_column;  // per block, -1 if none
  int columns = 0, rows = 0;

  int add_column(double lower, double upper) {
    column_lower.push_back(lower);
    column_upper.push_back(upper);
    return columns++;
  }
  int add_row(double lower, double upper) {
    row_lower.push_back(lower);
    row_upper.push_back(upper);
    return rows++;
  }
  void add_entry(int row, int column, double entry) {
    row_index.push_back(row);
    column_index.push_back(column);
    value.push_back(entry);
  }
};

// The edges of the friction cone's inner approximation as (c, f_u, f_v):
// a contact vertex's force is a non-negative combination of them, so the
// program needs no friction rows (a sixth of the rows, and cheap pivots).
// They span exactly the cone that friction_rows bounds; none when friction
// is unbounded (then c >= 0 and f_u, f_v are free columns).
std::vector<Eigen::Vector3d> friction_edges(const EquilibriumOptions& options) {
  const double mu = options.friction;
  if (std::isinf(mu)) return {};
  if (mu == 0.0) return {Eigen::Vector3d(1, 0, 0)};
  std::vector<Eigen::Vector3d> edges;
  if (options.friction_model == FrictionModel::box) {
    for (const double u : {-1.0, 1.0}) {
      for (const double v : {-1.0, 1.0}) edges.emplace_back(1.0, mu * u, mu * v);
    }
    return edges;
  }
  const int m = options.friction_sides;
  for (int j = 0; j < m; ++j) {
    const double angle = 2 * M_PI * j / m;
    edges.emplace_back(1.0, mu * std::cos(angle), mu * std::sin(angle));
  }
  return edges;
}

EquilibriumProgram equilibrium_program(const Structure& structure, const EquilibriumProblem& problem,
                                       const EquilibriumOptions& options) {
  const double infinity = COIN_DBL_MAX;
  EquilibriumProgram program;
  // Balance rows first, equal to the right-hand side less the weights.
  for (int r = 0; r < problem.row_count; ++r) program.add_row(problem.rhs(r), problem.rhs(r));
  const int vertical = problem.vertical_row();
  // A column for the combination `unknowns` (c, s, f_u, f_v) of a group.
  auto add_combination = [&](const ForceGroup& group, const Eigen::Vector4d& unknowns, double lower,
                             double upper) {
    const int column = program.add_column(lower, upper);
    for (int r = 0; r < problem.block_rows; ++r) {
      if (group.row_a >= 0) {
        const double entry = group.on_a.row(r).dot(unknowns);
        if (entry != 0.0) program.add_entry(group.row_a + r, column, entry);
      }
      if (group.row_b >= 0) {
        const double entry = group.on_b.row(r).dot(unknowns);
        if (entry != 0.0) program.add_entry(group.row_b + r, column, entry);
      }
    }
  };

  const std::vector<Eigen::Vector3d> edges = friction_edges(options);
  for (const ForceGroup& group : problem.groups) {
    switch (group.kind) {
      case GroupKind::contact_vertex:
        if (edges.empty()) {
          add_combination(group, Eigen::Vector4d(1, 0, 0, 0), 0.0, infinity);
          add_combination(group, Eigen::Vector4d(0, 0, 1, 0), -infinity, infinity);
          add_combination(group, Eigen::Vector4d(0, 0, 0, 1), -infinity, infinity);
        }
        for (const Eigen::Vector3d& edge : edges) {
          add_combination(group, Eigen::Vector4d(edge(0), 0, edge(1), edge(2)), 0.0, infinity);
        }
        break;
      case GroupKind::cable:
      case GroupKind::bounded_cable:
        // Tension only, up to its bound; compression is what it lacks.
        add_combination(group, Eigen::Vector4d(1, 0, 0, 0), 0.0,
                        group.kind == GroupKind::bounded_cable ? group.bound : infinity);
        break;
      case GroupKind::slack:   // virtual torques are what a compression-only equilibrium lacks
      case GroupKind::weight:  // not in analysis problems
        break;
    }
  }

  program.multiplier_column.assign(structure.size(), -1);
  for (int j = 0; j < structure.size(); ++j) {
    const int row = problem.row_of_block[j];
    const double weight = structure.block(j).mass() * kGravity / problem.weight_unit;
    if (row < 0 || !(weight > 0.0)) continue;
    const int column = program.add_column(1.0, 1.0);
    program.multiplier_column[j] = column;
    program.add_entry(row + vertical, column, -weight);
    program.row_lower[row + vertical] -= weight;
    program.row_upper[row + vertical] -= weight;
  }
  return program;
}

const char* failure(int status) {
  switch (status) {
    case 3:
      return "stopped";
    case 4:
      return "numerical difficulties";
    default:
      return "unexpected simplex status";
  }
}

}  // namespace

LoadCapacity load_capacity(const Structure& structure, const AnalysisSettings& settings) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const EquilibriumProblem problem = build_equilibrium_problem(structure, settings.problem);
  const EquilibriumProgram program = equilibrium_program(structure, problem, settings.problem);

  LoadCapacity result;
  result.min.assign(structure.size(), kNaN);
  result.max.assign(structure.size(), kNaN);
  ClpSimplex simplex;
  simplex.setLogLevel(0);
  const CoinPackedMatrix matrix(true, program.row_index.data(), program.column_index.data(),
                                program.value.data(), static_cast<CoinBigIndex>(program.value.size()));
  const std::vector<double> no_objective(program.columns, 0.0);
  simplex.loadProblem(matrix, program.column_lower.data(), program.column_upper.data(),
                      no_objective.data(), program.row_lower.data(), program.row_upper.data());
  // Returns Clp's status: 0 optimal, 1 infeasible, 2 unbounded, else failed.
  // The as-built program from scratch by the dual simplex (about half the
  // primal's pivots on domes); each block's programs by the primal, whose
  // start (the as-built basis with the block's bounds widened) is feasible.
  auto solve = [&] {
    if (result.programs == 0) simplex.dual();
    else simplex.primal();
    ++result.programs;
    result.simplex_iterations += simplex.numberIterations();
    return simplex.status();
  };

  const int as_built = solve();
  // Every block's programs start from the as-built optimum, where its
  // multiple 1 is feasible: one block's extreme basis (a ray, when
  // unbounded) is a poor start for the next block's.
  const int variables = program.columns + program.rows;
  const std::vector<unsigned char> built_status(simplex.statusArray(), simplex.statusArray() + variables);
  const std::vector<double> built_columns(simplex.primalColumnSolution(),
                                          simplex.primalColumnSolution() + program.columns);
  const std::vector<double> built_rows(simplex.primalRowSolution(),
                                       simplex.primalRowSolution() + program.rows);
  auto restore = [&] {
    simplex.copyinStatus(built_status.data());
    std::copy(built_columns.begin(), built_columns.end(), simplex.primalColumnSolution());
    std::copy(built_rows.begin(), built_rows.end(), simplex.primalRowSolution());
  };
  const bool floating = !problem.floating_blocks.empty() || !problem.floating_junctions.empty();
  result.stable = as_built == 0 && !floating;
  if (as_built > 2) result.status = failure(as_built);
  for (int j = 0; j < structure.size() && result.status == "optimal"; ++j) {
    const int column = program.multiplier_column[j];
    if (column < 0) continue;
    simplex.setColumnBounds(column, 0.0, COIN_DBL_MAX);
    for (const double direction : {1.0, -1.0}) {
      if (as_built == 0) restore();
      simplex.setObjectiveCoefficient(column, direction);
      const int status = solve();
      if (status > 2) {
        result.status = failure(status);
        break;
      }
      if (status == 1) break;  // no multiple lets the rest stand
      const double bound = status == 2 ? std::numeric_limits<double>::infinity()
                                       : simplex.primalColumnSolution()[column];
      (direction > 0 ? result.min : result.max)[j] = bound;
    }
    if (std::isnan(result.max[j])) result.min[j] = kNaN;
    simplex.setObjectiveCoefficient(column, 0.0);
    simplex.setColumnBounds(column, 1.0, 1.0);
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace ashlar
