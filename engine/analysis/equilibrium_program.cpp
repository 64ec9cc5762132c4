#include "analysis/equilibrium_program.hpp"

#include <ClpEventHandler.hpp>
#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <cmath>
#include <limits>

#include "core/interrupt.hpp"

namespace ashlar {

std::vector<Eigen::Vector4d> EquilibriumProgram::group_unknowns(const EquilibriumProblem& problem,
                                                                const double* x) const {
  std::vector<Eigen::Vector4d> unknowns(problem.groups.size(), Eigen::Vector4d::Zero());
  for (int c = 0; c < columns; ++c) {
    if (column_group[c] >= 0) unknowns[column_group[c]] += x[c] * column_unknowns[c];
  }
  return unknowns;
}

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
    const double angle = 2 * kPi * j / m;
    edges.emplace_back(1.0, mu * std::cos(angle), mu * std::sin(angle));
  }
  return edges;
}

double friction_needed(const EquilibriumOptions& options, double c, double f_u, double f_v) {
  double reach = 0.0;  // the largest f . n_j over the sides' outward normals, per unit apothem
  if (options.friction_model == FrictionModel::box) {
    reach = std::max(std::abs(f_u), std::abs(f_v));
  } else {
    const int m = options.friction_sides;
    for (int j = 0; j < m; ++j) {
      const double facing = (2 * j + 1) * kPi / m;
      reach = std::max(reach, f_u * std::cos(facing) + f_v * std::sin(facing));
    }
    reach /= std::cos(kPi / m);
  }
  if (reach <= 0.0) return 0.0;
  return c > 0.0 ? reach / c : std::numeric_limits<double>::infinity();
}

int EquilibriumProgram::add_group_column(const EquilibriumProblem& problem, int k, const Eigen::Vector4d& unknowns,
                                         double lower, double upper) {
  const ForceGroup& group = problem.groups[k];
  const int column = add_column(lower, upper, k, unknowns);
  const Eigen::Matrix<double, 6, 4> on_a = group.on_a(problem.block_rows);
  for (int r = 0; r < problem.block_rows; ++r) {
    if (group.row_a >= 0) {
      const double entry = on_a.row(r).dot(unknowns);
      if (entry != 0.0) add_entry(group.row_a + r, column, entry);
    }
    if (group.row_b >= 0) {
      const double entry = group.on_b.row(r).dot(unknowns);
      if (entry != 0.0) add_entry(group.row_b + r, column, entry);
    }
  }
  return column;
}

EquilibriumProgram equilibrium_program(const EquilibriumProblem& problem, const EquilibriumOptions& options) {
  const double infinity = std::numeric_limits<double>::max();
  EquilibriumProgram program;
  program.rows = problem.row_count;
  program.row_lower.assign(problem.rhs.data(), problem.rhs.data() + problem.row_count);
  program.row_upper = program.row_lower;

  const std::vector<Eigen::Vector3d> edges = friction_edges(options);
  for (int k = 0; k < static_cast<int>(problem.groups.size()); ++k) {
    const ForceGroup& group = problem.groups[k];
    switch (group.kind) {
      case GroupKind::contact_vertex:
        if (edges.empty()) {
          program.add_group_column(problem, k, Eigen::Vector4d(1, 0, 0, 0), 0.0, infinity);
          program.add_group_column(problem, k, Eigen::Vector4d(0, 0, 1, 0), -infinity, infinity);
          program.add_group_column(problem, k, Eigen::Vector4d(0, 0, 0, 1), -infinity, infinity);
        }
        for (const Eigen::Vector3d& edge : edges) {
          program.add_group_column(problem, k, Eigen::Vector4d(edge(0), 0, edge(1), edge(2)), 0.0, infinity);
        }
        break;
      case GroupKind::cable:
      case GroupKind::bounded_cable:
        // Tension only, up to its bound; compression is what it lacks.
        program.add_group_column(problem, k, Eigen::Vector4d(1, 0, 0, 0), 0.0,
                                 group.kind == GroupKind::bounded_cable ? group.bound : infinity);
        break;
      case GroupKind::slack:   // virtual torques are what a compression-only equilibrium lacks
      case GroupKind::weight:  // not in analysis problems
        break;
    }
  }
  return program;
}

void load_program(ClpSimplex& simplex, const EquilibriumProgram& program, IterationTally* tally) {
  // Explicit sizes: a trailing row or column without entries still counts.
  CoinPackedMatrix matrix(true, program.row_index.data(), program.column_index.data(),
                          program.value.data(), static_cast<CoinBigIndex>(program.value.size()));
  matrix.setDimensions(program.rows, program.columns);
  const std::vector<double> no_objective(program.columns, 0.0);
  simplex.setLogLevel(0);
  simplex.loadProblem(matrix, program.column_lower.data(), program.column_upper.data(),
                      no_objective.data(), program.row_lower.data(), program.row_upper.data());
  stop_on_request(simplex, tally);
}

namespace {

// Clp asks after every iteration, the barrier's too; 0 stops it with
// status 5. Clp works on clones, which share the tally.
class StopOnRequest : public ClpEventHandler {
public:
  explicit StopOnRequest(IterationTally* tally) : tally_(tally) {}
  int event(Event which) override {
    if (which != endOfIteration) return -1;
    if (tally_) {
      ++tally_->iterations;
      if (tally_->progress) tally_->progress(tally_->iterations, kTotalUnknown);
    }
    return stop_requested() ? 0 : -1;
  }
  ClpEventHandler* clone() const override { return new StopOnRequest(*this); }

private:
  IterationTally* tally_;
};

}  // namespace

void stop_on_request(ClpSimplex& simplex, IterationTally* tally) {
  StopOnRequest handler(tally);
  simplex.passInEventHandler(&handler);  // Clp keeps a clone
}

MarginStatus clp_failure(int status) {
  switch (status) {
    case 3:
      return MarginStatus::stopped;
    case 4:
      return MarginStatus::numerical_difficulties;
    case kClpInterrupted:
      return MarginStatus::interrupted;
    default:
      return MarginStatus::unexpected;
  }
}

}  // namespace ashlar
