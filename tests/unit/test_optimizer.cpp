// The design space's constraints and the optimisers, on synthetic objectives
// (weighted squared distances of positions to targets, exact gradients)
// whose constrained minimisers are known in closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "optimize/planar_chart.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/structure_optimization.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// Blocks (as face loops and vertices) and free points of a design.
struct DesignModel {
  std::vector<std::vector<FaceLoop>> faces;
  DesignPoint design;

  int add_box(const Vec3& size, const Vec3& center) {
    const Block block = make_box(size, center);
    faces.push_back(block.faces());
    design.block_vertices.push_back(block.vertices());
    return static_cast<int>(faces.size()) - 1;
  }
  int add_point(const Vec3& p) {
    design.points.push_back(p);
    return static_cast<int>(design.points.size()) - 1;
  }
};

Vec3 position(const DesignPoint& design, const PositionRef& ref) {
  if (ref.block == PositionRef::kFreePoint) return design.points[ref.index];
  return design.block_vertices[ref.block][ref.index];
}

Vec3& position(DesignPoint& design, const PositionRef& ref) {
  if (ref.block == PositionRef::kFreePoint) return design.points[ref.index];
  return design.block_vertices[ref.block][ref.index];
}

// The vertex of `block` at p (exactly).
PositionRef vertex_at(const DesignModel& model, int block, const Vec3& p) {
  const auto& vertices = model.design.block_vertices[block];
  for (size_t k = 0; k < vertices.size(); ++k) {
    if (vertices[k] == p) return PositionRef::vertex(block, static_cast<int>(k));
  }
  ADD_FAILURE() << "no vertex at " << p.transpose();
  return {};
}

// The face of `block` whose outward normal is `normal`.
FaceRef face_facing(const DesignModel& model, int block, const Vec3& normal) {
  const auto planes = face_planes(model.design.block_vertices[block], model.faces[block]);
  for (size_t f = 0; f < planes.size(); ++f) {
    if (planes[f].normal.dot(normal) > 0.999) return FaceRef{block, static_cast<int>(f)};
  }
  ADD_FAILURE() << "no face facing " << normal.transpose();
  return {};
}

DesignPoint zero_like(const DesignPoint& design) {
  DesignPoint zero = design;
  for (auto& vertices : zero.block_vertices) {
    for (Vec3& v : vertices) v.setZero();
  }
  for (Vec3& p : zero.points) p.setZero();
  return zero;
}

struct Target {
  PositionRef ref;
  Vec3 target;
  double weight = 1.0;
};

// sum of weight |x - target|^2 with its exact gradient.
DesignEvaluation squared_distances(const DesignPoint& design, const std::vector<Target>& targets) {
  DesignEvaluation evaluation;
  evaluation.gradient = zero_like(design);
  for (const Target& t : targets) {
    const Vec3 offset = position(design, t.ref) - t.target;
    evaluation.value += t.weight * offset.squaredNorm();
    position(evaluation.gradient, t.ref) += 2.0 * t.weight * offset;
  }
  return evaluation;
}

// Largest distance of a face vertex from its face's (Newell) plane, as a
// fraction of its block's size.
double planarity_error(const DesignPoint& design, const std::vector<std::vector<FaceLoop>>& faces) {
  double worst = 0.0;
  for (size_t b = 0; b < faces.size(); ++b) {
    const auto& vertices = design.block_vertices[b];
    Box3 bounds;
    for (const Vec3& v : vertices) bounds.add(v);
    const auto planes = face_planes(vertices, faces[b]);
    for (size_t f = 0; f < faces[b].size(); ++f) {
      for (int k : faces[b][f]) {
        const double off = std::abs(planes[f].normal.dot(vertices[k]) - planes[f].offset);
        worst = std::max(worst, off / bounds.diagonal());
      }
    }
  }
  return worst;
}

double volume_of(const DesignModel& model, const DesignPoint& design, int block) {
  return mass_properties(design.block_vertices[block], model.faces[block]).volume;
}

OptimizeSettings precise(OptimizeMethod method) {
  OptimizeSettings settings;
  settings.method = method;
  settings.max_iterations = 500;
  settings.gradient_tolerance = 1e-10;
  settings.value_tolerance = 0.0;
  return settings;
}

const OptimizeMethod kMethods[] = {OptimizeMethod::lbfgs, OptimizeMethod::gradient};

void expect_near(const Vec3& actual, const Vec3& expected, double tolerance, const char* what) {
  EXPECT_LT((actual - expected).norm(), tolerance)
      << what << ": " << actual.transpose() << " instead of " << expected.transpose();
}

// Two unit boxes side by side along x, sharing the face x = 1.
DesignModel two_boxes() {
  DesignModel model;
  model.add_box(Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.5));
  model.add_box(Vec3(1, 1, 1), Vec3(1.5, 0.5, 0.5));
  return model;
}

// Every vertex of block a pulled by shift_a, of block b by shift_b.
std::vector<Target> shifted_blocks(const DesignModel& model, const Vec3& shift_a, const Vec3& shift_b) {
  std::vector<Target> targets;
  for (int b = 0; b < 2; ++b) {
    const auto& vertices = model.design.block_vertices[b];
    for (size_t k = 0; k < vertices.size(); ++k) {
      targets.push_back({PositionRef::vertex(b, static_cast<int>(k)),
                         vertices[k] + (b == 0 ? shift_a : shift_b)});
    }
  }
  return targets;
}

}  // namespace

TEST(DesignSpace, WeldsCoincidentVerticesAndCountsSharedFacesOnce) {
  const DesignModel model = two_boxes();
  const DesignSpace space(model.faces, model.design);
  EXPECT_EQ(space.position_variable_count(), 12 * 3);  // 16 vertices, 4 pairs welded
  // 12 quads, the shared one once, each a plane of 3 variables and 4 nodes.
  EXPECT_EQ(space.variable_count(), 12 * 3 + 11 * 3);
  EXPECT_EQ(space.constraint_count(), 11 * 4);
  EXPECT_DOUBLE_EQ(space.model_size(), std::sqrt(6.0));
  EXPECT_EQ(space.start(), Eigen::VectorXd::Zero(69));
}

TEST(DesignSpace, ChartGradientMatchesFiniteDifferences) {
  DesignModel model = two_boxes();
  model.add_box(Vec3(2, 1, 0.5), Vec3(1, 0.5, 1.25));  // on both: T-junctions under it
  const std::vector<Target> targets = {
      {PositionRef::vertex(0, 7), Vec3(1.3, 1.2, 1.4)},
      {PositionRef::vertex(1, 2), Vec3(1.9, 1.4, -0.2)},
      {PositionRef::vertex(2, 5), Vec3(2.4, -0.3, 1.1)},
      {PositionRef::vertex(2, 6), Vec3(-0.2, 1.3, 1.8)},
  };
  DesignConstraints kept, mirrored;
  kept.keep_normal = {face_facing(model, 2, Vec3::UnitZ())};
  kept.fixed = {PositionRef::vertex(0, 0)};
  mirrored.mirror = MirrorPlane{Vec3(1, 0, 0), Vec3::UnitX()};
  for (const DesignConstraints& constraints : {DesignConstraints{}, kept, mirrored}) {
    const DesignSpace space(model.faces, model.design, constraints);
    const PlanarChart chart(space, space.start());
    EXPECT_EQ(chart.rank(), space.constraint_count());  // independent equations
    const auto value_at = [&](const Eigen::VectorXd& z) {
      const std::optional<Eigen::VectorXd> y = chart.project(z);
      EXPECT_TRUE(y.has_value());
      return squared_distances(space.design(*y), targets).value;
    };
    Eigen::VectorXd z(space.variable_count());
    for (int i = 0; i < z.size(); ++i) z[i] = 0.02 * std::sin(1.7 * i + 0.3);
    const Eigen::VectorXd y = *chart.project(z);
    EXPECT_LT(planarity_error(space.design(y), model.faces), 1e-10);
    const Eigen::VectorXd gradient =
        chart.pull_back(y, space.reduce(squared_distances(space.design(y), targets).gradient));
    const double h = 1e-5;
    for (int i = 0; i < z.size(); ++i) {
      Eigen::VectorXd plus = z, minus = z;
      plus[i] += h;
      minus[i] -= h;
      const double central = (value_at(plus) - value_at(minus)) / (2 * h);
      EXPECT_NEAR(gradient[i], central, 1e-6 * (1 + std::abs(central))) << "variable " << i;
    }
  }
}

TEST(Optimizer, WeldedVerticesMeetHalfwayBetweenTheirTargets) {
  const DesignModel model = two_boxes();
  const Vec3 shift_a(0.1, -0.2, 0.3), shift_b(-0.3, 0.2, 0.1);
  const auto targets = shifted_blocks(model, shift_a, shift_b);
  const DesignSpace space(model.faces, model.design);
  for (OptimizeMethod method : kMethods) {
    const OptimizeResult result = optimize_design(
        space, [&](const DesignPoint& d) { return squared_distances(d, targets); },
        precise(method));
    EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
    EXPECT_NEAR(result.history.back().value, 2 * (shift_a - shift_b).squaredNorm(), 1e-9);
    for (int b = 0; b < 2; ++b) {
      for (int k = 0; k < 8; ++k) {
        const Vec3& start = model.design.block_vertices[b][k];
        const Vec3 shift = start.x() == 1.0 ? 0.5 * (shift_a + shift_b)
                           : b == 0         ? shift_a
                                            : shift_b;
        expect_near(result.design.block_vertices[b][k], start + shift, 1e-5, "vertex");
      }
    }
  }
}

TEST(Optimizer, FixedBlocksVerticesAndPointsStay) {
  DesignModel model = two_boxes();
  const int fixed_point = model.add_point(Vec3(3, 0, 0));
  const int free_point = model.add_point(Vec3(3, 1, 0));
  auto targets = shifted_blocks(model, Vec3(0.2, 0.2, 0.2), Vec3(0.3, -0.1, 0.2));
  targets.push_back({PositionRef::point(fixed_point), Vec3(4, 0, 0)});
  targets.push_back({PositionRef::point(free_point), Vec3(4, 2, 1)});
  DesignConstraints constraints;
  constraints.fixed_blocks = {0};
  constraints.fixed = {PositionRef::point(fixed_point)};
  const DesignSpace space(model.faces, model.design, constraints);
  EXPECT_EQ(space.position_variable_count(), 4 * 3 + 3);  // B's far face and one point
  const OptimizeResult result = optimize_design(
      space, [&](const DesignPoint& d) { return squared_distances(d, targets); },
      precise(OptimizeMethod::lbfgs));
  EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
  for (int b = 0; b < 2; ++b) {
    for (int k = 0; k < 8; ++k) {
      const Vec3& start = model.design.block_vertices[b][k];
      const bool moves = b == 1 && start.x() == 2.0;
      const Vec3 expected = moves ? start + Vec3(0.3, -0.1, 0.2) : start;
      expect_near(result.design.block_vertices[b][k], expected, 1e-6, "vertex");
    }
  }
  EXPECT_EQ(result.design.points[fixed_point], Vec3(3, 0, 0));
  expect_near(result.design.points[free_point], Vec3(4, 2, 1), 1e-6, "free point");
}

TEST(Optimizer, MoveTogetherSharesOneDisplacement) {
  DesignModel model;
  const int box = model.add_box(Vec3(1, 1, 1), Vec3(0, 0, 0));
  const int p = model.add_point(Vec3(5, 0, 0));
  const int q = model.add_point(Vec3(6, 0, 0));
  DesignConstraints constraints;
  constraints.move_together.push_back({PositionRef::point(p), PositionRef::point(q)});
  std::vector<PositionRef> whole_box;
  for (int k = 0; k < 8; ++k) whole_box.push_back(PositionRef::vertex(box, k));
  constraints.move_together.push_back(whole_box);
  const PositionRef corner = vertex_at(model, box, Vec3(0.5, 0.5, 0.5));
  const std::vector<Target> targets = {
      {PositionRef::point(p), Vec3(5.2, 0.4, 0)},
      {PositionRef::point(q), Vec3(6.4, 0, -0.2)},
      {corner, Vec3(0.9, 0.2, 0.6)},
  };
  const DesignSpace space(model.faces, model.design, constraints);
  EXPECT_EQ(space.position_variable_count(), 6);
  const OptimizeResult result = optimize_design(
      space, [&](const DesignPoint& d) { return squared_distances(d, targets); },
      precise(OptimizeMethod::lbfgs));
  EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
  const Vec3 shared(0.3, 0.2, -0.1);  // the mean of (0.2, 0.4, 0) and (0.4, 0, -0.2)
  expect_near(result.design.points[p], Vec3(5, 0, 0) + shared, 1e-6, "p");
  expect_near(result.design.points[q], Vec3(6, 0, 0) + shared, 1e-6, "q");
  const Vec3 translation = Vec3(0.9, 0.2, 0.6) - Vec3(0.5, 0.5, 0.5);
  for (int k = 0; k < 8; ++k) {
    expect_near(result.design.block_vertices[box][k],
                model.design.block_vertices[box][k] + translation, 1e-6, "box vertex");
  }
}

TEST(Optimizer, MirrorSymmetryMirrorsDisplacementsAndKeepsPlanePointsInIt) {
  DesignModel model;
  const int p = model.add_point(Vec3(-1, 0, 0));
  const int q = model.add_point(Vec3(1, 0, 0));
  const int r = model.add_point(Vec3(0, 0, 1));
  const int box = model.add_box(Vec3(2, 1, 1), Vec3(0, 3.5, 0.5));
  const PositionRef corner = vertex_at(model, box, Vec3(1, 4, 1));
  const std::vector<Target> targets = {
      {PositionRef::point(p), Vec3(-1.3, 0.2, 0.1)},
      {PositionRef::point(q), Vec3(1.1, 0.4, -0.3)},
      {PositionRef::point(r), Vec3(0.5, 0.3, 1.2)},
      {corner, Vec3(1.5, 4, 1)},
  };
  DesignConstraints constraints;
  constraints.mirror = MirrorPlane{Vec3::Zero(), Vec3(2, 0, 0)};
  const DesignSpace space(model.faces, model.design, constraints);
  for (OptimizeMethod method : kMethods) {
    const OptimizeResult result = optimize_design(
        space, [&](const DesignPoint& d) { return squared_distances(d, targets); },
        precise(method));
    EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
    // d_p minimises |d - a|^2 + |R d - b|^2: d = (a + R b) / 2.
    expect_near(result.design.points[p], Vec3(-1.2, 0.3, -0.1), 1e-6, "p");
    expect_near(result.design.points[q], Vec3(1.2, 0.3, -0.1), 1e-6, "q");
    expect_near(result.design.points[r], Vec3(0, 0.3, 1.2), 1e-6, "r");
    // The box stretches symmetrically: the corner's partner mirrors it.
    expect_near(position(result.design, corner), Vec3(1.5, 4, 1), 1e-5, "corner");
    const auto& vertices = result.design.block_vertices[box];
    for (const Vec3& v : vertices) {
      const Vec3 image(-v.x(), v.y(), v.z());
      double nearest = 1e9;
      for (const Vec3& w : vertices) nearest = std::min(nearest, (w - image).norm());
      EXPECT_LT(nearest, 1e-12) << "no mirror image of " << v.transpose();
    }
    EXPECT_LT(planarity_error(result.design, model.faces), 1e-10);
  }
}

TEST(Optimizer, MaxDisplacementBoundsEveryCoordinate) {
  DesignModel model;
  const int p = model.add_point(Vec3(0, 0, 0));
  const int q = model.add_point(Vec3(1, 0, 0));
  const std::vector<Target> targets = {
      {PositionRef::point(p), Vec3(2, -0.05, 0)},
      {PositionRef::point(q), Vec3(-2, 0, 1)},
  };
  DesignConstraints constraints;
  constraints.max_displacement = 0.5;
  const DesignSpace space(model.faces, model.design, constraints);
  for (OptimizeMethod method : kMethods) {
    double worst = 0.0;
    const OptimizeResult result = optimize_design(
        space,
        [&](const DesignPoint& d) {
          worst = std::max({worst, d.points[p].cwiseAbs().maxCoeff(),
                            (d.points[q] - Vec3(1, 0, 0)).cwiseAbs().maxCoeff()});
          return squared_distances(d, targets);
        },
        precise(method));
    // Both points end against max_displacement, the gradient pushing past it.
    EXPECT_EQ(result.status, OptimizeStatus::at_bound) << result.message;
    EXPECT_STREQ(status_name(result.status), "at_bound");
    EXPECT_LE(worst, 0.5);
    expect_near(result.design.points[p], Vec3(0.5, -0.05, 0), 1e-6, "p");
    expect_near(result.design.points[q], Vec3(0.5, 0, 0.5), 1e-6, "q");
  }
}

TEST(Optimizer, KeptNormalRaisesTheWholeTopFace) {
  DesignModel model;
  const int box = model.add_box(Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.5));
  DesignConstraints constraints;
  for (int k = 0; k < 8; ++k) {
    if (model.design.block_vertices[box][k].z() == 0.0) {
      constraints.fixed.push_back(PositionRef::vertex(box, k));
    }
  }
  constraints.keep_normal = {face_facing(model, box, Vec3::UnitZ())};
  const PositionRef corner = vertex_at(model, box, Vec3(1, 1, 1));
  const std::vector<Target> targets = {{corner, Vec3(1, 1, 1.5)}};
  const DesignSpace space(model.faces, model.design, constraints);
  for (OptimizeMethod method : kMethods) {
    const OptimizeResult result = optimize_design(
        space, [&](const DesignPoint& d) { return squared_distances(d, targets); },
        precise(method));
    EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
    EXPECT_LT(result.history.back().value, 1e-12);
    for (int k = 0; k < 8; ++k) {
      const Vec3& start = model.design.block_vertices[box][k];
      const Vec3 expected = start.z() == 1.0 ? start + Vec3(0, 0, 0.5) : start;
      expect_near(result.design.block_vertices[box][k], expected, 1e-6, "vertex");
    }
  }
}

TEST(Optimizer, EveryEvaluatedDesignHasPlanarFacesAndClosedContacts) {
  DesignModel model = two_boxes();
  const int top = model.add_box(Vec3(2, 1, 0.5), Vec3(1, 0.5, 1.25));
  const int base = model.add_box(Vec3(2, 1, 0.2), Vec3(1, 0.5, -0.1));
  // Vertices of the two middle boxes that lie on the faces of the others.
  const std::vector<std::pair<PositionRef, FaceRef>> junctions = {
      {vertex_at(model, 0, Vec3(1, 0, 1)), face_facing(model, top, -Vec3::UnitZ())},
      {vertex_at(model, 0, Vec3(1, 1, 1)), face_facing(model, top, -Vec3::UnitZ())},
      {vertex_at(model, 0, Vec3(1, 0, 0)), face_facing(model, base, Vec3::UnitZ())},
      {vertex_at(model, 1, Vec3(1, 1, 0)), face_facing(model, base, Vec3::UnitZ())},
  };
  // Pulls that no planar design meets exactly.
  const std::vector<Target> targets = {
      {PositionRef::vertex(0, 7), Vec3(1.3, 1.2, 1.4)},
      {PositionRef::vertex(1, 2), Vec3(1.9, 1.4, -0.2)},
      {PositionRef::vertex(2, 5), Vec3(2.4, -0.3, 1.1)},
      {PositionRef::vertex(2, 6), Vec3(-0.2, 1.3, 1.8)},
      {PositionRef::vertex(0, 0), Vec3(-0.5, -0.5, 0.4)},
  };
  DesignConstraints constraints;
  constraints.fixed_blocks = {base};
  const DesignSpace space(model.faces, model.design, constraints);
  for (OptimizeMethod method : kMethods) {
    double worst_face = 0.0, worst_gap = 0.0;
    int calls = 0;
    OptimizeSettings settings;
    settings.method = method;
    settings.max_iterations = 30;
    const OptimizeResult result = optimize_design(
        space,
        [&](const DesignPoint& d) {
          ++calls;
          worst_face = std::max(worst_face, planarity_error(d, model.faces));
          for (const auto& [vertex, face] : junctions) {
            const FacePlane plane =
                face_planes(d.block_vertices[face.block], {model.faces[face.block][face.face]})[0];
            worst_gap =
                std::max(worst_gap, std::abs(plane.normal.dot(position(d, vertex)) - plane.offset));
          }
          return squared_distances(d, targets);
        },
        settings);
    EXPECT_EQ(calls, result.evaluations);
    EXPECT_LT(worst_face, 1e-10);
    EXPECT_LT(worst_gap, 1e-10);
    EXPECT_LT(result.history.back().value, 0.5 * result.history.front().value) << result.message;
    EXPECT_GT(result.history.size(), 5u) << result.message;
    for (int k = 0; k < 8; ++k) {
      EXPECT_EQ(result.design.block_vertices[base][k], model.design.block_vertices[base][k]);
    }
  }
}

TEST(Optimizer, RunningBondWallKeepsItsBedJointsPlanar) {
  // Three courses of three bricks, the middle course offset by half a brick:
  // each bed joint is one plane through the T-junctions of the vertical joints.
  DesignModel model;
  for (int course = 0; course < 3; ++course) {
    const double offset = course == 1 ? 0.5 : 0.0;
    for (int brick = 0; brick < 3; ++brick) {
      model.add_box(Vec3(1, 0.5, 0.25), Vec3(brick + offset + 0.5, 0.25, 0.125 + 0.25 * course));
    }
  }
  DesignConstraints constraints;
  constraints.fixed_blocks = {0, 1, 2};
  const DesignSpace space(model.faces, model.design, constraints);
  EXPECT_EQ(PlanarChart(space, space.start()).rank(), space.constraint_count());
  // The top course's far corner pulled up and out.
  const std::vector<Target> targets = {
      {vertex_at(model, 8, Vec3(3, 0.5, 0.75)), Vec3(3.2, 0.6, 0.95)}};
  for (OptimizeMethod method : kMethods) {
    double worst_face = 0.0, worst_joint = 0.0;
    OptimizeSettings settings;
    settings.method = method;
    settings.max_iterations = 20;
    const OptimizeResult result = optimize_design(
        space,
        [&](const DesignPoint& d) {
          worst_face = std::max(worst_face, planarity_error(d, model.faces));
          // Every vertex at the upper bed joint lies on the top course's beds.
          const FacePlane bed = face_planes(d.block_vertices[7], {model.faces[7][0]})[0];
          for (int b = 3; b < 9; ++b) {
            for (int k = 0; k < 8; ++k) {
              if (model.design.block_vertices[b][k].z() != 0.5) continue;
              const double gap = bed.normal.dot(d.block_vertices[b][k]) - bed.offset;
              worst_joint = std::max(worst_joint, std::abs(gap));
            }
          }
          return squared_distances(d, targets);
        },
        settings);
    EXPECT_LT(worst_face, 1e-10);
    EXPECT_LT(worst_joint, 1e-10);
    EXPECT_LT(result.history.back().value, 0.01 * result.history.front().value) << result.message;
  }
}

TEST(Optimizer, FlatStripHeldAtBothEndsStaysFlat) {
  // Five unit boxes in a row, the end ones fixed: the top, bottom and sides
  // of the three free ones are flat strips held at both ends, which could
  // stay flat or fold; their planarity equations are singular where the two
  // meet, so the strips stay flat.
  DesignModel model;
  for (int box = 0; box < 5; ++box) model.add_box(Vec3(1, 1, 1), Vec3(box + 0.5, 0.5, 0.5));
  DesignConstraints constraints;
  constraints.fixed_blocks = {0, 4};
  const DesignSpace space(model.faces, model.design, constraints);
  EXPECT_EQ(PlanarChart(space, space.start()).rank(), space.constraint_count());
  const PositionRef corner = vertex_at(model, 2, Vec3(3, 0, 1));
  const std::vector<Target> targets = {{corner, Vec3(3.1, 0, 1.5)}};
  for (OptimizeMethod method : kMethods) {
    double worst = 0.0;
    const OptimizeResult result = optimize_design(
        space,
        [&](const DesignPoint& d) {
          worst = std::max(worst, planarity_error(d, model.faces));
          return squared_distances(d, targets);
        },
        precise(method));
    EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
    EXPECT_LT(worst, 1e-10);
    // It slides along the edge where the top and the front strips meet.
    expect_near(position(result.design, corner), Vec3(3.1, 0, 1), 1e-6, "corner");
    EXPECT_NEAR(result.history.back().value, 0.25, 1e-9);
  }
}

TEST(Optimizer, MinBlockVolumeHoldsAtEveryEvaluation) {
  DesignModel model;
  const int box = model.add_box(Vec3(1, 1, 1), Vec3(0.5, 0.5, 0.5));
  DesignConstraints constraints;
  std::vector<Target> targets;
  for (int k = 0; k < 8; ++k) {
    const Vec3& v = model.design.block_vertices[box][k];
    if (v.z() == 0.0) {
      constraints.fixed.push_back(PositionRef::vertex(box, k));
    } else {
      targets.push_back({PositionRef::vertex(box, k), Vec3(v.x(), v.y(), 0.2)});
    }
  }
  constraints.min_block_volume = 0.5;
  const DesignSpace space(model.faces, model.design, constraints);
  for (OptimizeMethod method : kMethods) {
    double smallest = 1.0;
    OptimizeSettings settings;
    settings.method = method;
    settings.max_iterations = 200;
    const OptimizeResult result = optimize_design(
        space,
        [&](const DesignPoint& d) {
          smallest = std::min(smallest, volume_of(model, d, box));
          return squared_distances(d, targets);
        },
        settings);
    EXPECT_GE(smallest, 0.5);
    const double volume = volume_of(model, result.design, box);
    EXPECT_GE(volume, 0.5);
    EXPECT_LT(volume, 0.501) << result.message;  // pressed against the bound
  }
}

TEST(Optimizer, StopsAtTheFirstStableEvaluation) {
  DesignModel model;
  const int p = model.add_point(Vec3(0, 0, 0));
  const std::vector<Target> targets = {{PositionRef::point(p), Vec3(1, 2, 0)}};
  const DesignSpace space(model.faces, model.design);
  for (OptimizeMethod method : kMethods) {
    int calls = 0, stable_calls = 0;
    bool called_after_stable = false;
    OptimizeSettings settings;
    settings.method = method;
    settings.initial_step = 0.25;
    const OptimizeResult result = optimize_design(
        space,
        [&](const DesignPoint& d) {
          called_after_stable |= stable_calls > 0;
          ++calls;
          DesignEvaluation evaluation = squared_distances(d, targets);
          evaluation.stable = evaluation.value < 0.5;
          stable_calls += evaluation.stable;
          return evaluation;
        },
        settings);
    EXPECT_EQ(result.status, OptimizeStatus::stable);
    EXPECT_STREQ(status_name(result.status), "stable");
    EXPECT_TRUE(result.stable);
    EXPECT_TRUE(result.history.back().stable);
    EXPECT_FALSE(called_after_stable);
    EXPECT_EQ(stable_calls, 1);
    EXPECT_EQ(result.evaluations, calls);
    EXPECT_LT((result.design.points[p] - Vec3(1, 2, 0)).squaredNorm(), 0.5);
  }
}

TEST(Optimizer, LbfgsNeedsFewerIterationsThanGradientDescentWhenIllConditioned) {
  DesignModel model;
  const int p = model.add_point(Vec3(0, 0, 0));
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d hessian = rotation * Vec3(1, 30, 300).asDiagonal() * rotation.transpose();
  const Vec3 minimiser(0.4, -0.3, 0.2);
  const DesignSpace space(model.faces, model.design);
  const auto objective = [&](const DesignPoint& d) {
    const Vec3 offset = d.points[p] - minimiser;
    DesignEvaluation evaluation;
    evaluation.value = 0.5 * offset.dot(hessian * offset);
    evaluation.gradient = zero_like(d);
    evaluation.gradient.points[p] = hessian * offset;
    return evaluation;
  };
  OptimizeSettings settings = precise(OptimizeMethod::lbfgs);
  settings.max_iterations = 300;
  const OptimizeResult lbfgs = optimize_design(space, objective, settings);
  settings.method = OptimizeMethod::gradient;
  const OptimizeResult gradient = optimize_design(space, objective, settings);
  EXPECT_EQ(lbfgs.status, OptimizeStatus::converged) << lbfgs.message;
  expect_near(lbfgs.design.points[p], minimiser, 1e-8, "L-BFGS");
  EXPECT_LT(lbfgs.history.size(), 30u);
  EXPECT_GT(gradient.history.size(), 3 * lbfgs.history.size()) << gradient.message;
  EXPECT_LT(lbfgs.evaluations, gradient.evaluations);
}

TEST(Optimizer, HistoryRecordsEveryAcceptedIterate) {
  DesignModel model;
  const int p = model.add_point(Vec3(0, 0, 0));
  const std::vector<Target> targets = {{PositionRef::point(p), Vec3(1, 0, 0)}};
  const DesignSpace space(model.faces, model.design);
  std::vector<OptimizeStep> seen;
  OptimizeSettings settings;
  settings.method = OptimizeMethod::gradient;
  settings.max_iterations = 4;
  settings.initial_step = 0.1;
  settings.on_step = [&](const OptimizeStep& step) { seen.push_back(step); };
  const OptimizeResult result = optimize_design(
      space, [&](const DesignPoint& d) { return squared_distances(d, targets); }, settings);
  EXPECT_EQ(result.status, OptimizeStatus::max_iterations);
  EXPECT_STREQ(status_name(result.status), "max_iterations");
  ASSERT_EQ(result.history.size(), 5u);
  ASSERT_EQ(seen.size(), 5u);
  EXPECT_DOUBLE_EQ(result.history[0].value, 1.0);
  EXPECT_EQ(result.history[0].step, 0.0);
  EXPECT_NEAR(result.history[1].step, 0.1, 1e-12);  // the first step is initial_step long
  EXPECT_NEAR(result.history[1].value, 0.81, 1e-12);
  for (size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].iteration, static_cast<int>(i));
    EXPECT_EQ(seen[i].value, result.history[i].value);
    if (i > 0) {
      EXPECT_LT(seen[i].value, seen[i - 1].value);
      EXPECT_GE(seen[i].seconds, seen[i - 1].seconds);
    }
  }
  // The last step's length is how far the point moved in it.
  EXPECT_NEAR(result.history[4].step,
              std::abs(std::sqrt(result.history[4].value) - std::sqrt(result.history[3].value)),
              1e-12);

  // An exception from on_step reaches the caller unchanged.
  settings.on_step = [](const OptimizeStep& step) {
    if (step.iteration == 2) throw std::range_error("enough");
  };
  EXPECT_THROW(
      optimize_design(
          space, [&](const DesignPoint& d) { return squared_distances(d, targets); }, settings),
      std::range_error);
}

TEST(Optimizer, GeometryErrorsShortenTheStepAndOtherErrorsEndTheRun) {
  DesignModel model;
  const int p = model.add_point(Vec3(0, 0, 0));
  const std::vector<Target> targets = {{PositionRef::point(p), Vec3(1, 0, 0)}};
  const DesignSpace space(model.faces, model.design);
  // A design past x = 0.3 is "invalid geometry": the optimum lies at 0.3.
  const OptimizeResult walled = optimize_design(
      space,
      [&](const DesignPoint& d) {
        if (d.points[p].x() > 0.3) throw GeometryError("block 1 is inverted");
        return squared_distances(d, targets);
      },
      precise(OptimizeMethod::gradient));
  EXPECT_LE(walled.design.points[p].x(), 0.3);
  EXPECT_GT(walled.design.points[p].x(), 0.29) << walled.message;
  EXPECT_EQ(walled.status, OptimizeStatus::line_search_failed);
  EXPECT_TRUE(contains(walled.message, "(the last trial design was rejected: block 1 is inverted)"))
      << walled.message;

  int calls = 0;
  const OptimizeResult failed = optimize_design(
      space,
      [&](const DesignPoint& d) {
        if (++calls == 3) throw InvalidArgument("analysis: the solver ran out of memory");
        return squared_distances(d, targets);
      },
      precise(OptimizeMethod::lbfgs));
  EXPECT_EQ(failed.status, OptimizeStatus::evaluation_failed);
  EXPECT_STREQ(status_name(failed.status), "evaluation_failed");
  EXPECT_TRUE(contains(failed.message, "the solver ran out of memory")) << failed.message;
  EXPECT_EQ(failed.evaluations, 3);
  EXPECT_EQ(failed.history.size(), 2u);  // the start and one accepted step

  const OptimizeResult misshapen =
      optimize_design(space, [&](const DesignPoint&) { return DesignEvaluation{}; }, {});
  EXPECT_EQ(misshapen.status, OptimizeStatus::evaluation_failed);
  EXPECT_TRUE(contains(misshapen.message, "design gradient: 0 points, expected 1"))
      << misshapen.message;
}

TEST(Optimizer, ParametersStayWithinTheirBounds) {
  // Rosenbrock: unbounded minimum at (1, 1); with a <= 0.5 the minimum is
  // (0.5, 0.25), where the value is 0.25.
  const auto rosenbrock = [](const Eigen::VectorXd& x) {
    ParameterEvaluation evaluation;
    evaluation.value = std::pow(1 - x[0], 2) + 100 * std::pow(x[1] - x[0] * x[0], 2);
    evaluation.gradient = Eigen::Vector2d(-2 * (1 - x[0]) - 400 * x[0] * (x[1] - x[0] * x[0]),
                                          200 * (x[1] - x[0] * x[0]));
    return evaluation;
  };
  const Eigen::Vector2d initial(-1.2, 1.0);
  for (OptimizeMethod method : kMethods) {
    for (const double a_max : {0.5, 2.0}) {
      const Eigen::Vector2d lower(-2, -1), upper(a_max, 2);
      bool inside = true;
      OptimizeSettings settings = precise(method);
      settings.max_iterations = method == OptimizeMethod::lbfgs ? 200 : 20;
      const ParameterResult result = optimize_parameters(
          lower, upper, initial,
          [&](const Eigen::VectorXd& x) {
            inside &= (x.array() >= lower.array()).all() && (x.array() <= upper.array()).all();
            return rosenbrock(x);
          },
          settings);
      EXPECT_TRUE(inside);
      for (size_t i = 1; i < result.history.size(); ++i) {
        EXPECT_LT(result.history[i].value, result.history[i - 1].value);
      }
      EXPECT_EQ(result.active_bounds.size(), 2u);
      if (method == OptimizeMethod::lbfgs) {
        // With a <= 0.5 the minimum is held by the bound on a, which it reports.
        EXPECT_EQ(result.status, a_max == 0.5 ? OptimizeStatus::at_bound : OptimizeStatus::converged)
            << result.message;
        EXPECT_EQ(result.active_bounds[0], a_max == 0.5 ? BoundSide::upper : BoundSide::none);
        EXPECT_EQ(result.active_bounds[1], BoundSide::none);
        const Eigen::Vector2d expected =
            a_max == 0.5 ? Eigen::Vector2d(0.5, 0.25) : Eigen::Vector2d(1.0, 1.0);
        EXPECT_LT((result.parameters - expected).norm(), 1e-5)
            << result.parameters.transpose() << ", " << result.message;
      } else {
        EXPECT_EQ(result.status, OptimizeStatus::max_iterations) << result.message;
        EXPECT_LT(result.history.back().value, 0.5 * result.history.front().value);
      }
    }
  }
}

TEST(Optimizer, BadConstraintsThrowNamingTheBadThing) {
  DesignModel model = two_boxes();
  model.add_box(Vec3(1, 1, 1), Vec3(0.5, 0.5, 1.5));
  model.add_point(Vec3(5, 5, 5));
  const auto error_with = [&](DesignConstraints constraints) {
    return error_of([&] { DesignSpace(model.faces, model.design, constraints); });
  };
  DesignConstraints c;
  c.keep_normal = {FaceRef{2, 8}};
  EXPECT_EQ(error_with(c), "keep_normal: block 3 has no face 9 (it has 6)");
  c = {};
  c.keep_normal = {FaceRef{7, 0}};
  EXPECT_EQ(error_with(c), "keep_normal: block 8 does not exist (the design has 3 blocks)");
  c = {};
  c.fixed_blocks = {3};
  EXPECT_EQ(error_with(c), "fixed_blocks: block 4 does not exist (the design has 3 blocks)");
  c = {};
  c.fixed = {PositionRef::vertex(1, 8)};
  EXPECT_EQ(error_with(c), "fixed: block 2 has no vertex 9 (it has 8)");
  c = {};
  c.move_together = {{PositionRef::point(0)}, {PositionRef::point(1)}};
  EXPECT_EQ(error_with(c), "move_together: group 2: there is no point 2 (the design has 1 points)");
  c = {};
  c.move_together = {{}};
  EXPECT_EQ(error_with(c), "move_together: group 1 is empty");
  c = {};
  c.mirror = MirrorPlane{Vec3::Zero(), Vec3::Zero()};
  EXPECT_EQ(error_with(c), "mirror: the plane's normal must be a finite, non-zero vector");
  c = {};
  c.mirror = MirrorPlane{Vec3(1, 0, 0), Vec3::UnitX()};
  EXPECT_TRUE(contains(error_with(c), "has no mirror image across the plane")) << error_with(c);
  c = {};
  c.max_displacement = 0.0;
  EXPECT_EQ(error_with(c), "max_displacement must be a number > 0 (m) or infinite, got 0");
  c = {};
  c.weld_tolerance = -1.0;
  EXPECT_EQ(error_with(c), "weld_tolerance must be a finite number >= 0 (m), got -1");
  c = {};
  c.min_block_volume = 2.0;
  EXPECT_TRUE(contains(error_with(c),
                       "the initial design is not admissible: block 1 has volume 1 "
                       "m^3, below min_block_volume (2 m^3)"))
      << error_with(c);
  c = {};
  c.weld_tolerance = 2.0;
  EXPECT_TRUE(contains(error_with(c),
                       "welding: vertices 1 and 2 of block 1 are closer than the "
                       "weld tolerance (2 m)"))
      << error_with(c);

  DesignModel mismatched = model;
  mismatched.faces.pop_back();
  EXPECT_EQ(error_of([&] { DesignSpace(mismatched.faces, mismatched.design); }),
            "design: 2 blocks of faces but 3 blocks of vertices");
  mismatched = model;
  mismatched.faces[1][2][1] = 8;
  EXPECT_EQ(error_of([&] { DesignSpace(mismatched.faces, mismatched.design); }),
            "design: face 3 of block 2 refers to vertex 9, but the block has 8");
}

TEST(Optimizer, BadSettingsAndParameterBoundsThrow) {
  DesignModel model;
  model.add_point(Vec3(0, 0, 0));
  const DesignSpace space(model.faces, model.design);
  const DesignObjective objective = [](const DesignPoint& d) {
    return squared_distances(d, {{PositionRef::point(0), Vec3(1, 0, 0)}});
  };
  OptimizeSettings settings;
  settings.max_iterations = -1;
  EXPECT_EQ(error_of([&] { optimize_design(space, objective, settings); }),
            "optimize: max_iterations must be >= 0, got -1");
  settings = {};
  settings.value_tolerance = std::nan("");
  EXPECT_EQ(error_of([&] { optimize_design(space, objective, settings); }),
            "optimize: value_tolerance must be a finite number >= 0, got nan");

  const ParameterObjective quadratic = [](const Eigen::VectorXd& x) {
    return ParameterEvaluation{x.squaredNorm(), false, 2 * x};
  };
  EXPECT_EQ(error_of([&] {
              optimize_parameters(Eigen::Vector2d(0, 1), Eigen::Vector2d(1, 0),
                                  Eigen::Vector2d(0.5, 0.5), quadratic);
            }),
            "optimize parameters: parameter 2: its bounds [1, 0] are not an interval");
  EXPECT_EQ(error_of([&] {
              optimize_parameters(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1),
                                  Eigen::Vector2d(0.5, 1.5), quadratic);
            }),
            "optimize parameters: parameter 2: its initial value 1.5 is not within its bounds "
            "[0, 1]");
  EXPECT_EQ(error_of([&] {
              optimize_parameters(Eigen::Vector2d(0, 0), Eigen::Vector3d(1, 1, 1),
                                  Eigen::Vector2d(0.5, 0.5), quadratic);
            }),
            "optimize parameters: lower, upper and initial must have equal sizes, got 2, 3 and 2");
}

TEST(StructureOptimization, AThinArchIsMadeToStandByItsVerticesOrItsThickness) {
  // A 16-voussoir arch (centreline radius 5 m, no sliding) at t = 0.4 m,
  // below its minimum 5 x 0.1071 = 0.536 m: ashlar.optimize's two paths,
  // in C++. Moving vertices (supports fixed, springings held, symmetric
  // about x = 0), the result stands and its supports and springing faces
  // have not moved; through a generator of thickness, the thickness found
  // stands and is no less than the minimum.
  AnalysisSettings analysis;
  analysis.problem.friction = std::numeric_limits<double>::infinity();
  const Structure arch = semicircular_arch(16, 0.4);
  ASSERT_FALSE(analyze_equilibrium(arch, analysis).stable);

  DesignConstraints constraints;
  for (int i = 0; i < arch.size(); ++i) {
    if (arch.is_support(i)) constraints.fixed_blocks.push_back(i);
  }
  hold_faces_on_fixed_blocks(arch, constraints);
  EXPECT_EQ(constraints.fixed.size(), 8u);  // the two springing faces' vertices
  constraints.mirror = MirrorPlane{Vec3::Zero(), Vec3::UnitX()};
  OptimizeSettings settings;
  settings.initial_step = 0.01;
  int reports = 0;
  const StructureOptimization moved =
      optimize_structure(arch, constraints, analysis, settings, [&](double, double) { ++reports; });
  EXPECT_TRUE(moved.result.stable) << moved.result.message;
  EXPECT_TRUE(analyze_equilibrium(*moved.structure, analysis).stable);
  EXPECT_EQ(reports, moved.result.evaluations);
  for (int i = 0; i < arch.size(); ++i) {
    if (arch.is_support(i)) {
      EXPECT_EQ(moved.structure->block(i).vertices(), arch.block(i).vertices());
    }
  }
  for (const PositionRef& held : constraints.fixed) {
    EXPECT_EQ(moved.structure->block(held.block).vertices()[held.index],
              arch.block(held.block).vertices()[held.index]);
  }

  const StructureGenerator thickness = [](const Eigen::VectorXd& t) {
    return std::make_shared<Structure>(semicircular_arch(16, t(0)));
  };
  const GeneratedOptimization thickened =
      optimize_generated(thickness, {"thickness"}, Eigen::VectorXd::Constant(1, 0.3),
                         Eigen::VectorXd::Constant(1, 1.5), Eigen::VectorXd::Constant(1, 0.4), analysis, settings);
  EXPECT_TRUE(thickened.result.stable) << thickened.result.message;
  EXPECT_GE(thickened.result.parameters(0), 5 * 0.1071 - 1e-3);
  EXPECT_TRUE(analyze_equilibrium(*thickened.structure, analysis).stable);
}

namespace {

// Minimise x + y subject to x y >= 1 (the least sum is 2, at (1, 1)); the
// margin is a verdict with a violation 1 - x y and its gradient only where
// it is violated, as an analysis's penalty.
ParameterEvaluation sum_of(const Eigen::VectorXd& p) {
  ParameterEvaluation e;
  e.value = p.sum();
  e.gradient = Eigen::VectorXd::Ones(p.size());
  return e;
}

MarginCheck hyperbola(const Eigen::VectorXd& p, bool gradient) {
  MarginCheck m;
  m.margin = p[0] * p[1];
  m.feasible = m.margin >= 1.0;
  m.violation = std::max(0.0, 1.0 - m.margin);
  if (gradient) m.violation_gradient = m.feasible ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(-p[1], -p[0]);
  return m;
}

}  // namespace

TEST(TargetOptimizer, LeastSumOnAHyperbolaFromEitherSide) {
  const Eigen::Vector2d lower(0.1, 0.1), upper(4, 4);
  for (OptimizeMethod method : kMethods) {  // not used: the result is the same
    for (const Eigen::Vector2d& start : {Eigen::Vector2d(3, 2), Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(4, 0.3)}) {
      bool inside = true;
      OptimizeSettings settings;
      settings.method = method;
      settings.max_iterations = 200;
      const ParameterResult result = optimize_parameters_to_target(
          lower, upper, start, sum_of,
          [&](const Eigen::VectorXd& p, bool gradient) {
            inside &= (p.array() >= lower.array()).all() && (p.array() <= upper.array()).all();
            return hyperbola(p, gradient);
          },
          settings);
      EXPECT_TRUE(inside);
      EXPECT_TRUE(result.stable) << result.message;
      EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
      EXPECT_GE(result.parameters.prod(), 1.0);
      // The boundary is bisected to 1e-3 of the range (3.9) per segment; the
      // least sum to about that.
      EXPECT_NEAR(result.parameters.sum(), 2.0, 4e-3) << result.parameters.transpose() << ": " << result.message;
      EXPECT_NEAR(result.margin, result.parameters.prod(), 1e-15);
      EXPECT_EQ(result.active_bounds, std::vector<BoundSide>(2, BoundSide::none));
      for (size_t k = 1; k < result.history.size(); ++k) {
        EXPECT_TRUE(result.history[k].stable || !result.history[k - 1].stable);  // once feasible, it stays
      }
      EXPECT_TRUE(result.history.back().stable);
    }
  }
}

TEST(TargetOptimizer, OneParameterEndsWithinTheBracketAboveAThreshold) {
  // Feasible from x = 0.537 up (a step verdict with no gradient at all):
  // the least x is found from above and from below, within
  // bracket_tolerance x (upper - lower) above it.
  const double threshold = 0.537;
  const MarginFunction step = [&](const Eigen::VectorXd& p, bool) {
    MarginCheck m;
    m.feasible = p[0] >= threshold;
    m.violation = std::max(0.0, threshold - p[0]);
    return m;
  };
  const MarginFunction sloped = [&](const Eigen::VectorXd& p, bool gradient) {
    MarginCheck m = step(p, gradient);
    if (gradient) m.violation_gradient = Eigen::VectorXd::Constant(1, m.feasible ? 0.0 : -1.0);
    return m;
  };
  const Eigen::VectorXd lower = Eigen::VectorXd::Constant(1, 0.2), upper = Eigen::VectorXd::Constant(1, 1.0);
  for (const double start : {0.3, 0.6, 0.95}) {
    for (const double tolerance : {1e-3, 1e-5}) {
      OptimizeSettings settings;
      settings.bracket_tolerance = tolerance;
      const ParameterResult result = optimize_parameters_to_target(
          lower, upper, Eigen::VectorXd::Constant(1, start), sum_of, start < threshold ? sloped : step, settings);
      EXPECT_EQ(result.status, OptimizeStatus::converged) << result.message;
      EXPECT_TRUE(result.on_boundary);
      EXPECT_GE(result.parameters[0], threshold);
      EXPECT_LE(result.parameters[0], threshold + tolerance * 0.8) << "from " << start;
    }
  }
}

TEST(TargetOptimizer, ABoundThatHoldsTheResultIsReported) {
  const MarginFunction above = [](const Eigen::VectorXd& p, bool gradient) {
    MarginCheck m;
    m.feasible = p[0] >= 0.537;
    m.violation = std::max(0.0, 0.537 - p[0]);
    if (gradient) m.violation_gradient = Eigen::VectorXd::Constant(1, m.feasible ? 0.0 : -1.0);
    return m;
  };
  // The least feasible value lies below the lower bound: at_bound, feasible.
  const ParameterResult low = optimize_parameters_to_target(Eigen::VectorXd::Constant(1, 0.7),
                                                            Eigen::VectorXd::Constant(1, 2.0),
                                                            Eigen::VectorXd::Constant(1, 1.5), sum_of, above);
  EXPECT_EQ(low.status, OptimizeStatus::at_bound) << low.message;
  EXPECT_TRUE(low.stable);
  EXPECT_FALSE(low.on_boundary);
  EXPECT_EQ(low.parameters[0], 0.7);
  EXPECT_EQ(low.active_bounds, std::vector<BoundSide>{BoundSide::lower});
  // Nothing up to the upper bound is feasible: the restoration stops there.
  const ParameterResult high = optimize_parameters_to_target(Eigen::VectorXd::Constant(1, 0.2),
                                                             Eigen::VectorXd::Constant(1, 0.5),
                                                             Eigen::VectorXd::Constant(1, 0.3), sum_of, above);
  EXPECT_EQ(high.status, OptimizeStatus::at_bound) << high.message;
  EXPECT_FALSE(high.stable);
  EXPECT_EQ(high.parameters[0], 0.5);
  EXPECT_EQ(high.active_bounds, std::vector<BoundSide>{BoundSide::upper});
  EXPECT_NE(high.message.find("the margin does not reach the target"), std::string::npos) << high.message;
}

TEST(StructureOptimization, LeastThicknessThatStandsIsTheArchsMinimum) {
  // 16 voussoirs, R = 5 m, no sliding: the polyhedral arch's minimum is
  // t/R = 0.10708 (DESIGN.md, verification). The least volume that stands,
  // from either side of it, is within bracket_tolerance x (upper - lower)
  // = 1e-3 x 1.2 m above it; with a geometric factor of 1.5 the thickness
  // is 1.5 times that.
  AnalysisSettings analysis;
  analysis.problem.friction = std::numeric_limits<double>::infinity();
  const StructureGenerator thickness = [](const Eigen::VectorXd& t) {
    return std::make_shared<Structure>(semicircular_arch(16, t(0)));
  };
  const double minimum = 5 * 0.10708;
  const Eigen::VectorXd lower = Eigen::VectorXd::Constant(1, 0.3), upper = Eigen::VectorXd::Constant(1, 1.5);
  for (const double start : {0.4, 0.9}) {
    const GeneratedOptimization r = optimize_generated_to_target(
        thickness, {"thickness"}, lower, upper, Eigen::VectorXd::Constant(1, start), analysis, MarginTarget{},
        Material::volume, OptimizeSettings{});
    EXPECT_EQ(r.result.status, OptimizeStatus::converged) << r.result.message;
    EXPECT_GE(r.result.parameters(0), minimum - 5e-4);
    EXPECT_LE(r.result.parameters(0), minimum + 1.2e-3 + 5e-4) << "from " << start;
    EXPECT_TRUE(analyze_equilibrium(*r.structure, analysis).stable);
  }
  MarginTarget factor;
  factor.kind = MarginKind::geometric_factor;
  factor.value = 1.5;
  const GeneratedOptimization g = optimize_generated_to_target(
      thickness, {"thickness"}, lower, upper, Eigen::VectorXd::Constant(1, 0.6), analysis, factor, Material::weight,
      OptimizeSettings{});
  EXPECT_EQ(g.result.status, OptimizeStatus::converged) << g.result.message;
  EXPECT_NEAR(g.result.parameters(0) / 1.5, minimum, 1.2e-3);
}

TEST(StructureOptimization, JointWidthsAndSecondDifferencesOfAnArch) {
  // Depth 1 m, thickness 0.4 m: every joint (and springing) is a 0.4 x 1
  // rectangle, so the least width is the thickness.
  const Structure arch = semicircular_arch(8, 0.4);
  EXPECT_NEAR(least_joint_width(arch, ContactOptions{}), 0.4, 1e-12);
  // The intrados's joint corners at y = -0.5: points of a circle of radius
  // 4.8 at angles k pi / 8, whose second differences are the chord polygon's
  // 2 r (cos(pi / 8) - 1) towards the centre, each.
  const DesignPoint design = design_of(arch);
  std::vector<PositionRef> intrados;
  for (int b = 0; b < arch.size(); ++b) {
    if (arch.is_support(b)) continue;
    const std::vector<Vec3>& v = arch.block(b).vertices();
    for (size_t k = 0; k < v.size(); ++k) {
      if (std::abs(v[k].y() + 0.5) < 1e-12 && std::hypot(v[k].x(), v[k].z()) < 4.9 &&
          std::none_of(intrados.begin(), intrados.end(),
                       [&](const PositionRef& r) { return (position(design, r) - v[k]).norm() < 1e-9; })) {
        intrados.push_back(PositionRef::vertex(b, static_cast<int>(k)));
      }
    }
  }
  ASSERT_EQ(intrados.size(), 9u);
  std::sort(intrados.begin(), intrados.end(), [&](const PositionRef& a, const PositionRef& b) {
    return std::atan2(position(design, a).z(), position(design, a).x()) >
           std::atan2(position(design, b).z(), position(design, b).x());
  });
  const double each = 2 * 4.8 * (1 - std::cos(M_PI / 8));
  EXPECT_NEAR(second_differences(design, {intrados}), 7 * each * each, 1e-12);
  EXPECT_EQ(second_differences(design, {{intrados[0], intrados[1]}}), 0.0);
}
