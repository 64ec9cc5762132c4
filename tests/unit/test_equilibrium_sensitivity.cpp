// The envelope-theorem derivatives of the optimal penalty against central
// differences of re-solved problems whose data (contact positions, frames,
// centroids, weights, units) is perturbed one piece at a time.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <functional>

#include "analysis/equilibrium_sensitivity.hpp"
#include "analysis/interior_point.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// The problem's data, editable, and how to turn it back into a problem.
struct ProblemData {
  std::vector<Vec3> positions;                  // per contact vertex
  std::vector<std::array<Vec3, 3>> frames;      // per contact vertex: n, u, v
  std::vector<Vec3> centroids;                  // per block
  std::vector<double> weights;                  // per block, N
  double weight_unit = 1.0, length_unit = 1.0;
};

ProblemData data_of(const Structure& s, const EquilibriumProblem& p) {
  ProblemData d;
  for (int k = 0; k < p.contact_vertex_count; ++k) {
    const ForceGroup& v = p.groups[k];
    const Interface& c = (*s.interfaces())[v.source];
    d.positions.push_back(c.vertices[v.component]);
    d.frames.push_back({c.normal, c.u, c.v});
  }
  for (int i = 0; i < s.size(); ++i) {
    d.centroids.push_back(s.block(i).centroid());
    d.weights.push_back(s.block(i).mass() * kGravity);
  }
  d.weight_unit = p.weight_unit;
  d.length_unit = p.length_unit;
  return d;
}

// Rebuilds A and b from `d` as build_equilibrium_problem does.
EquilibriumProblem with_data(const Structure& s, EquilibriumProblem p, const ProblemData& d) {
  const std::array<int, 6>& rows = balance_rows(p.block_rows == 3);
  for (int k = 0; k < p.contact_vertex_count; ++k) {
    ForceGroup& v = p.groups[k];
    Interface contact = (*s.interfaces())[v.source];
    contact.normal = d.frames[k][0];
    contact.u = d.frames[k][1];
    contact.v = d.frames[k][2];
    v.on_b = contact_vertex_effect(contact, d.positions[k], d.centroids[v.block_b], d.length_unit, rows);
    v.lever = (d.centroids[v.block_a] - d.centroids[v.block_b]) / d.length_unit;
  }
  for (int i = 0; i < s.size(); ++i) {
    const int row = p.row_of_block[i];
    if (row < 0) continue;
    Eigen::Matrix<double, 6, 1> external = Eigen::Matrix<double, 6, 1>::Zero();
    external(2) = d.weights[i] / d.weight_unit;
    for (const PointLoad& load : s.loads()) {
      if (load.block != i) continue;
      const Vec3 arm = (load.at - d.centroids[i]) / d.length_unit;
      external.head<3>() -= load.force / d.weight_unit;
      external.tail<3>() -= arm.cross(load.force / d.weight_unit);
    }
    for (int r = 0; r < p.block_rows; ++r) p.rhs(row + r) = external(rows[r]);
  }
  return p;
}

double optimal_penalty(const EquilibriumProblem& p, InteriorPointSolution* out = nullptr) {
  EquilibriumSolver solver(p);
  InteriorPointSolution solution;
  InteriorPointSettings settings;
  settings.tolerance = 1e-13;
  const InteriorPointInfo info = solver.solve(p, settings, solution);
  EXPECT_TRUE(info.status == SolverStatus::converged || info.status == SolverStatus::inaccurate);
  if (out) *out = solution;
  return info.objective;
}

// Checks every derivative of `s`'s penalty against central differences.
void expect_sensitivities_match(const Structure& s, const EquilibriumOptions& options) {
  const EquilibriumProblem problem = build_equilibrium_problem(s, options);
  const ProblemData base = data_of(s, problem);
  InteriorPointSolution solution;
  const double penalty = optimal_penalty(with_data(s, problem, base), &solution);
  ASSERT_GT(penalty, 1e-3) << "the structure must be unstable for a non-trivial gradient";
  const EquilibriumSensitivity sens = equilibrium_sensitivity(s, problem, solution);

  const double h = 1e-5;
  auto difference = [&](const std::function<void(ProblemData&, double)>& move) {
    ProblemData plus = base, minus = base;
    move(plus, h);
    move(minus, -h);
    return (optimal_penalty(with_data(s, problem, plus)) - optimal_penalty(with_data(s, problem, minus))) /
           (2 * h);
  };
  auto expect_close = [&](double analytic, double numeric, const std::string& what) {
    EXPECT_NEAR(analytic, numeric, 1e-4 * (1 + std::abs(numeric))) << what;
  };
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    for (int j = 0; j < 3; ++j) {
      const std::string at = " vertex " + std::to_string(k) + " axis " + std::to_string(j);
      expect_close(sens.vertex_position[k](j),
                   difference([&](ProblemData& d, double e) { d.positions[k](j) += e; }), "position" + at);
      for (int f = 0; f < 3; ++f) {
        expect_close(sens.vertex_frame[k](j, f),
                     difference([&](ProblemData& d, double e) { d.frames[k][f](j) += e; }),
                     "frame " + std::to_string(f) + at);
      }
    }
  }
  for (int i = 0; i < s.size(); ++i) {
    if (problem.row_of_block[i] < 0) continue;
    for (int j = 0; j < 3; ++j) {
      expect_close(sens.block_centroid[i](j),
                   difference([&](ProblemData& d, double e) { d.centroids[i](j) += e; }),
                   "centroid of block " + std::to_string(i));
    }
    expect_close(sens.block_weight[i] * base.weight_unit,
                 difference([&](ProblemData& d, double e) { d.weights[i] += e * base.weight_unit; }),
                 "weight of block " + std::to_string(i));
  }
  expect_close(sens.weight_unit * base.weight_unit,
               difference([&](ProblemData& d, double e) { d.weight_unit *= 1 + e; }), "weight unit");
  expect_close(sens.length_unit * base.length_unit,
               difference([&](ProblemData& d, double e) { d.length_unit *= 1 + e; }), "length unit");
}

Structure overhanging_stack_with_load() {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  s.add(box({1, 1, 0.5}, {0, 0, 0.25}));
  s.add(box({1, 1, 0.5}, {0.7, 0.1, 0.75}));
  s.add_load({2, {-300, 200, -500}, {0.9, 0.2, 1.0}});
  return s;
}

}  // namespace

TEST(EquilibriumSensitivity, MatchesDifferencesOnAnOverhangingStackWithALoad) {
  EquilibriumOptions no_sliding;
  no_sliding.friction = std::numeric_limits<double>::infinity();
  expect_sensitivities_match(overhanging_stack_with_load(), no_sliding);
}

TEST(EquilibriumSensitivity, MatchesDifferencesWithFriction) {
  EquilibriumOptions friction;
  friction.friction = 0.3;
  expect_sensitivities_match(overhanging_stack_with_load(), friction);
}

TEST(EquilibriumSensitivity, MatchesDifferencesOnAPlanarProblem) {
  Structure s;
  s.add(box({3, 1, 0.2}, {0, 0, -0.1}), true);
  s.add(box({1, 1, 0.5}, {0, 0, 0.25}));
  s.add(box({1, 1, 0.5}, {0.7, 0, 0.75}));
  s.add_load({2, {-300, 0, -500}, {0.9, 0, 1.0}});
  s.set_planar(true);
  expect_sensitivities_match(s, {});
}
