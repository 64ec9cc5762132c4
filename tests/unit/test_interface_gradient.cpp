// Interface gradient: the closed-form chain rule from contact vertices and
// frames to block vertices, against central differences of contact detection.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "geometry/block_builders.hpp"
#include "structure/interface_gradient.hpp"
#include "structure/structure.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// Central differences of detection itself agree with the closed form to this,
// relative to the gradient's largest component.
constexpr double kAgreement = 1e-6;

// Wider than any step below, so perturbed faces still count as touching.
ContactOptions contact_options() {
  ContactOptions options;
  options.tolerance = 1e-4;
  return options;
}

// Blocks as plain vertex and face lists, so that tests can move single vertices.
struct Model {
  std::vector<std::vector<Vec3>> vertices;
  std::vector<std::vector<FaceLoop>> faces;

  void add(const Block& block) {
    vertices.push_back(block.vertices());
    faces.push_back(block.faces());
  }
  Structure build() const {
    Structure structure;
    for (size_t i = 0; i < vertices.size(); ++i) {
      structure.add(std::make_shared<const Block>(vertices[i], faces[i]));
    }
    return structure;
  }
};

// A tilted plane: a point, the unit normal and in-plane axes with e1 x e2 = normal.
struct TiltedPlane {
  Vec3 origin, normal, e1, e2;

  TiltedPlane(const Vec3& at, const Vec3& direction) : origin(at), normal(direction.normalized()) {
    e1 = normal.cross(Vec3::UnitY()).normalized();
    e2 = normal.cross(e1);
  }
  std::vector<Vec3> points(const std::vector<Vec2>& plane_points) const {
    std::vector<Vec3> out;
    for (const Vec2& q : plane_points) out.push_back(origin + q.x() * e1 + q.y() * e2);
    return out;
  }
};

// A polygon of the plane z = height, as 3D points.
std::vector<Vec3> at_height(const std::vector<Vec2>& polygon, double height) {
  std::vector<Vec3> out;
  for (const Vec2& q : polygon) out.emplace_back(q.x(), q.y(), height);
  return out;
}

Block tetrahedron(const std::vector<Vec3>& base, const Vec3& apex) {
  // The base runs counter-clockwise seen from the apex.
  return Block({base[0], base[1], base[2], apex}, {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}});
}

std::vector<InterfaceAdjoint> random_adjoints(const std::vector<Interface>& interfaces,
                                              unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto draw = [&] { return Vec3(uniform(random), uniform(random), uniform(random)); };
  std::vector<InterfaceAdjoint> adjoints(interfaces.size());
  for (size_t k = 0; k < interfaces.size(); ++k) {
    for (size_t j = 0; j < interfaces[k].vertices.size(); ++j) {
      adjoints[k].vertices.push_back(draw());
    }
    adjoints[k].normal = draw();
    adjoints[k].u = draw();
    adjoints[k].v = draw();
  }
  return adjoints;
}

size_t nearest(const std::vector<Vec3>& points, const Vec3& p) {
  size_t best = 0;
  for (size_t i = 1; i < points.size(); ++i) {
    if ((points[i] - p).norm() < (points[best] - p).norm()) best = i;
  }
  return best;
}

// f = sum of adjoint . quantity over the interfaces; perturbed interfaces and
// their vertices are matched to the reference ones by position, because a
// loop may start at another vertex after a move.
double objective(const std::vector<Interface>& reference, const std::vector<Interface>& moved,
                 const std::vector<InterfaceAdjoint>& adjoints) {
  EXPECT_EQ(moved.size(), reference.size());
  double f = 0.0;
  for (size_t k = 0; k < reference.size(); ++k) {
    const Interface* match = nullptr;
    for (const Interface& candidate : moved) {
      if (candidate.a != reference[k].a || candidate.b != reference[k].b) continue;
      if (!match || (candidate.center - reference[k].center).norm() <
                        (match->center - reference[k].center).norm()) {
        match = &candidate;
      }
    }
    if (!match || match->vertices.size() != reference[k].vertices.size()) {
      ADD_FAILURE() << "interface " << k << " lost or changed its vertex count under a move";
      return std::numeric_limits<double>::quiet_NaN();
    }
    for (size_t j = 0; j < reference[k].vertices.size(); ++j) {
      f += adjoints[k].vertices[j].dot(
          match->vertices[nearest(match->vertices, reference[k].vertices[j])]);
    }
    f += adjoints[k].normal.dot(match->normal) + adjoints[k].u.dot(match->u) +
         adjoints[k].v.dot(match->v);
  }
  return f;
}

using VertexRef = std::pair<int, int>;  // block, vertex

// Vertices at the same position in several blocks move together, as the
// optimiser welds them; every other vertex moves alone.
std::vector<std::vector<VertexRef>> welded_groups(const Model& model) {
  std::vector<std::vector<VertexRef>> groups;
  for (size_t i = 0; i < model.vertices.size(); ++i) {
    for (size_t k = 0; k < model.vertices[i].size(); ++k) {
      const Vec3& p = model.vertices[i][k];
      const auto same = std::find_if(groups.begin(), groups.end(), [&](const auto& group) {
        return model.vertices[group[0].first][group[0].second] == p;
      });
      if (same != groups.end()) {
        same->emplace_back(static_cast<int>(i), static_cast<int>(k));
      } else {
        groups.push_back({{static_cast<int>(i), static_cast<int>(k)}});
      }
    }
  }
  return groups;
}

struct GradientCheck {
  double relative_error = 0.0;  // max |difference - closed form| / max |closed form|
  double largest = 0.0;         // max |closed form|
  int welded = 0;               // groups of more than one vertex
};

// Compares accumulate_interface_gradient with central differences for every
// coordinate of every (welded group of) vertex.
GradientCheck check_gradient(const Model& model, unsigned seed) {
  const ContactOptions options = contact_options();
  const Structure structure = model.build();
  const std::vector<Interface> reference = *structure.interfaces(options);
  EXPECT_FALSE(reference.empty());
  const std::vector<InterfaceAdjoint> adjoints = random_adjoints(reference, seed);
  std::vector<std::vector<Vec3>> gradient;
  double smallest_block = std::numeric_limits<double>::infinity();
  for (int i = 0; i < structure.size(); ++i) {
    gradient.emplace_back(structure.block(i).vertices().size(), Vec3::Zero());
    smallest_block = std::min(smallest_block, structure.block(i).bounds().diagonal());
  }
  accumulate_interface_gradient(structure, options, adjoints, gradient);

  // Small enough that a vertex moved alone keeps its faces planar for validation.
  const double step = 5e-7 * smallest_block;
  GradientCheck check;
  double worst = 0.0;
  for (const std::vector<VertexRef>& group : welded_groups(model)) {
    if (group.size() > 1) ++check.welded;
    Vec3 closed_form = Vec3::Zero();
    for (const auto& [block, vertex] : group) closed_form += gradient[block][vertex];
    for (int axis = 0; axis < 3; ++axis) {
      double f[2];
      for (int side = 0; side < 2; ++side) {
        Model moved = model;
        for (const auto& [block, vertex] : group) {
          moved.vertices[block][vertex][axis] += side == 0 ? step : -step;
        }
        f[side] = objective(reference, *moved.build().interfaces(options), adjoints);
      }
      const double difference = (f[0] - f[1]) / (2.0 * step);
      worst = std::max(worst, std::abs(difference - closed_form[axis]));
      check.largest = std::max(check.largest, std::abs(closed_form[axis]));
    }
  }
  check.relative_error = worst / check.largest;
  return check;
}

// How many contact vertices sit on a vertex of block a, else on a vertex of
// block b, else on neither (crossings of edges), to show what a test exercises.
struct VertexKinds {
  int of_a = 0, of_b = 0, crossings = 0;
};

VertexKinds vertex_kinds(const Structure& structure, const Interface& contact) {
  const auto on_vertex_of = [&](int block, const Vec3& x) {
    for (const Vec3& p : structure.block(block).vertices()) {
      if ((p - x).norm() <= 1e-12) return true;
    }
    return false;
  };
  VertexKinds kinds;
  for (const Vec3& x : contact.vertices) {
    if (on_vertex_of(contact.a, x)) ++kinds.of_a;
    else if (on_vertex_of(contact.b, x)) ++kinds.of_b;
    else ++kinds.crossings;
  }
  return kinds;
}

void expect_kinds(const Model& model, int of_a, int of_b, int crossings) {
  const Structure structure = model.build();
  for (const Interface& contact : *structure.interfaces(contact_options())) {
    const VertexKinds kinds = vertex_kinds(structure, contact);
    EXPECT_EQ(kinds.of_a, of_a);
    EXPECT_EQ(kinds.of_b, of_b);
    EXPECT_EQ(kinds.crossings, crossings);
  }
}

// The longest edge must be unique: a tie makes u one-sided.
void expect_unique_longest_edges(const Model& model) {
  const Structure structure = model.build();
  for (const Interface& contact : *structure.interfaces(contact_options())) {
    std::vector<double> lengths;
    const size_t count = contact.vertices.size();
    for (size_t i = 0; i < count; ++i) {
      lengths.push_back((contact.vertices[(i + 1) % count] - contact.vertices[i]).norm());
    }
    std::sort(lengths.rbegin(), lengths.rend());
    EXPECT_GT(lengths[0] - lengths[1], 1e-3);
  }
}

void expect_agreement(const Model& model, unsigned seed, int welded) {
  expect_unique_longest_edges(model);
  const GradientCheck check = check_gradient(model, seed);
  std::ostringstream error;
  error << check.relative_error;
  ::testing::Test::RecordProperty("max_relative_error", error.str());
  EXPECT_GT(check.largest, 0.1);
  EXPECT_LE(check.relative_error, kAgreement);
  EXPECT_EQ(check.welded, welded);
}

// An irregular quadrilateral (unique longest edge), counter-clockwise.
const std::vector<Vec2> kIrregularQuad = {{-0.35, -0.2}, {0.5, -0.3}, {0.4, 0.25}, {-0.3, 0.2}};

Model small_on_large(bool small_first) {
  Model model;
  const Block large = make_box({2.0, 1.6, 0.5}, {0.1, 0.05, -0.25});
  const Block small = make_prism(at_height(kIrregularQuad, 0.0), {0.0, 0.0, 0.45});
  if (small_first) {
    model.add(small);
    model.add(large);
  } else {
    model.add(large);
    model.add(small);
  }
  return model;
}

// A box and an irregular prism overlapping at one corner of each: the contact
// has a vertex of each block and two crossings of their edges.
Model offset_blocks() {
  Model model;
  model.add(make_box({1.2, 1.0, 0.6}, {0.0, 0.0, -0.3}));
  const std::vector<Vec2> quad = {{0.0, 0.1}, {1.0, -0.05}, {1.1, 0.9}, {0.15, 0.8}};
  model.add(make_prism(at_height(quad, 0.0), {0.0, 0.0, 0.5}));
  return model;
}

// A convex pentagonal slab under a non-convex prism, both on a tilted plane,
// the upper one extruded obliquely.
Model tilted_contact() {
  const TiltedPlane plane({0.2, -0.1, 1.0}, {0.3, -0.2, 1.0});
  const std::vector<Vec2> lower = {{-0.7, -0.5}, {0.6, -0.6}, {0.8, 0.2}, {0.1, 0.7}, {-0.6, 0.4}};
  const std::vector<Vec2> upper = {{0.2, -0.2}, {1.2, -0.3}, {1.1, 0.6}, {0.6, 0.15}, {0.3, 0.5}};
  Model model;
  model.add(make_prism(plane.points(lower), -0.5 * plane.normal));
  model.add(make_prism(plane.points(upper), 0.4 * plane.normal + Vec3(0.1, 0.05, 0.0)));
  return model;
}

// Three voussoirs of an arch in the x-z plane with radial joints shared
// exactly; the joints are trapezoids, so their longest edge is unique.
Model voussoirs() {
  const double inner = 2.0, outer = 2.6;
  const auto joint = [&](double angle) {
    const Vec3 radial(std::cos(angle), 0.0, std::sin(angle));
    return std::vector<Vec3>{inner * radial, outer * radial + Vec3(0.0, -0.1, 0.0),
                             outer * radial + Vec3(0.0, 0.8, 0.0),
                             inner * radial + Vec3(0.0, 0.7, 0.0)};
  };
  const double angles[] = {0.5, 0.9, 1.35, 1.7};
  Model model;
  for (int i = 0; i < 3; ++i) model.add(make_loft(joint(angles[i]), joint(angles[i + 1])));
  return model;
}

// Two tetrahedra whose triangles overlap on a tilted plane: every vertex can
// move alone and the faces stay planar, so the normal's derivative is tested
// in every direction.
Model tetrahedra() {
  const TiltedPlane plane({-0.1, 0.3, 0.5}, {-0.25, 0.4, 1.0});
  const std::vector<Vec3> lower = plane.points({{-0.3, -0.3}, {0.9, -0.4}, {0.1, 0.9}});
  const std::vector<Vec3> upper = plane.points({{-0.2, -0.9}, {0.4, 0.2}, {-0.65, 0.25}});
  Model model;
  // Both triangles run counter-clockwise about the plane's normal; the lower
  // apex is behind the plane, so its base is listed the other way round.
  model.add(tetrahedron({lower[0], lower[2], lower[1]},
                        plane.origin - 0.7 * plane.normal + 0.1 * plane.e1));
  model.add(tetrahedron(upper, plane.origin + 0.6 * plane.normal - 0.2 * plane.e2));
  return model;
}

// A slab whose top is two coplanar faces split at x = 0, under a pentagonal
// prism that covers part of both: several faces of a on the contact plane,
// crossings on the edges of either.
Model split_top() {
  const std::vector<Vec3> vertices = {
      {-1, -0.5, -0.5}, {1, -0.5, -0.5}, {1, 0.5, -0.5}, {-1, 0.5, -0.5}, {-1, -0.5, 0},
      {0, -0.5, 0},     {1, -0.5, 0},    {1, 0.5, 0},    {0, 0.5, 0},     {-1, 0.5, 0}};
  const std::vector<FaceLoop> faces = {{0, 3, 2, 1},    {4, 5, 8, 9},       {5, 6, 7, 8},
                                       {0, 1, 6, 5, 4}, {2, 3, 9, 8, 7},    {0, 4, 9, 3},
                                       {1, 2, 7, 6}};
  const std::vector<Vec2> upper = {
      {-1.2, -0.3}, {0.6, -0.35}, {1.3, 0.1}, {0.2, 0.4}, {-1.3, 0.25}};
  Model model;
  model.add(Block(vertices, faces));
  model.add(make_prism(at_height(upper, 0.0), {0.0, 0.0, 0.4}));
  return model;
}

// An irregular prism under a second copy of its top, turned by 4e-5 rad
// about a skew axis and moved by 3.7e-5 m: two copies of one joint within the
// tolerance (1e-4 m), which meet on their mid-plane; every vertex can move
// alone.
Model mid_plane_joint() {
  const std::vector<Vec3> joint = at_height(kIrregularQuad, 0.0);
  const Eigen::AngleAxisd turn(4e-5, Vec3(1.0, 2.0, 0.5).normalized());
  std::vector<Vec3> copy;
  for (const Vec3& p : joint) copy.push_back(turn * p + Vec3(2e-5, -1e-5, 3e-5));
  Model model;
  model.add(make_prism(joint, {0.0, 0.0, -0.45}));
  model.add(make_prism(copy, {0.1, 0.05, 0.4}));
  return model;
}

}  // namespace

TEST(InterfaceGradient, SmallBlockOnLargeBlockIsFaceOfB) {
  const Model model = small_on_large(false);
  expect_kinds(model, 0, 4, 0);
  expect_agreement(model, 11, 0);
}

TEST(InterfaceGradient, SmallBlockOnLargeBlockIsFaceOfA) {
  const Model model = small_on_large(true);
  expect_kinds(model, 4, 0, 0);
  expect_agreement(model, 12, 0);
}

TEST(InterfaceGradient, OffsetBlocksCrossEdges) {
  const Model model = offset_blocks();
  expect_kinds(model, 1, 1, 2);
  expect_agreement(model, 13, 0);
}

TEST(InterfaceGradient, TiltedNonConvexContact) {
  const Model model = tilted_contact();
  const Structure structure = model.build();
  ASSERT_EQ(structure.interfaces(contact_options())->size(), 1u);
  EXPECT_GT(std::abs((*structure.interfaces(contact_options()))[0].normal.x()), 0.2);
  expect_kinds(model, 1, 3, 2);
  expect_agreement(model, 14, 0);
}

TEST(InterfaceGradient, VoussoirsSharingJointsMoveWelded) {
  const Model model = voussoirs();
  ASSERT_EQ(model.build().interfaces(contact_options())->size(), 2u);
  expect_kinds(model, 4, 0, 0);
  expect_agreement(model, 15, 8);
}

TEST(InterfaceGradient, SharedJointIsAttributedToBlockA) {
  const Model model = voussoirs();
  const Structure structure = model.build();
  const ContactOptions options = contact_options();
  std::vector<InterfaceAdjoint> adjoints = random_adjoints(*structure.interfaces(options), 18);
  adjoints[1] = InterfaceAdjoint{};  // only the joint between voussoirs 1 and 2
  std::vector<std::vector<Vec3>> gradient;
  for (int i = 0; i < structure.size(); ++i) {
    gradient.emplace_back(structure.block(i).vertices().size(), Vec3::Zero());
  }
  accumulate_interface_gradient(structure, options, adjoints, gradient);
  int shared = 0;
  for (size_t k = 0; k < model.vertices[1].size(); ++k) {
    const auto& first = model.vertices[0];
    const auto in_first = std::find(first.begin(), first.end(), model.vertices[1][k]);
    if (in_first == first.end()) continue;
    ++shared;
    EXPECT_EQ(gradient[1][k], Vec3::Zero());
    EXPECT_GT(gradient[0][in_first - first.begin()].norm(), 1e-3);
  }
  EXPECT_EQ(shared, 4);
}

TEST(InterfaceGradient, MidPlaneJointReachesBothCopiesHalfEach) {
  const Model model = mid_plane_joint();
  const std::vector<Interface> found = *model.build().interfaces(contact_options());
  ASSERT_EQ(found.size(), 1u);
  ASSERT_TRUE(found[0].on_mid_plane);
  expect_kinds(model, 0, 0, 4);  // the midpoints are vertices of neither block
  expect_agreement(model, 21, 0);
}

TEST(InterfaceGradient, TetrahedraOnTiltedPlane) {
  const Model model = tetrahedra();
  ASSERT_EQ(model.build().interfaces(contact_options())->size(), 1u);
  expect_kinds(model, 1, 1, 2);
  expect_agreement(model, 16, 0);
}

TEST(InterfaceGradient, SeveralFacesOfOneBlockOnThePlane) {
  const Model model = split_top();
  expect_kinds(model, 0, 2, 4);
  expect_agreement(model, 17, 0);
}

TEST(InterfaceGradient, AddsToTheGivenGradientAndSkipsZeroAdjoints) {
  const Model model = offset_blocks();
  const Structure structure = model.build();
  const ContactOptions options = contact_options();
  const std::vector<InterfaceAdjoint> adjoints =
      random_adjoints(*structure.interfaces(options), 21);
  std::vector<std::vector<Vec3>> fresh = {std::vector<Vec3>(8, Vec3::Zero()),
                                          std::vector<Vec3>(8, Vec3::Zero())};
  accumulate_interface_gradient(structure, options, adjoints, fresh);
  std::vector<std::vector<Vec3>> primed = {std::vector<Vec3>(8, Vec3::Ones()),
                                           std::vector<Vec3>(8, Vec3::Ones())};
  accumulate_interface_gradient(structure, options, adjoints, primed);
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k < 8; ++k) {
      EXPECT_NEAR((primed[i][k] - fresh[i][k] - Vec3::Ones()).norm(), 0.0, 1e-15);
    }
  }
  std::vector<std::vector<Vec3>> untouched = primed;
  accumulate_interface_gradient(structure, options, {InterfaceAdjoint{}}, untouched);
  EXPECT_EQ(untouched, primed);
}

TEST(InterfaceGradient, RejectsMismatchedSizes) {
  const Structure structure = offset_blocks().build();
  const ContactOptions options = contact_options();
  std::vector<std::vector<Vec3>> gradient = {std::vector<Vec3>(8, Vec3::Zero()),
                                             std::vector<Vec3>(8, Vec3::Zero())};
  EXPECT_TRUE(contains(
      error_of([&] { accumulate_interface_gradient(structure, options, {}, gradient); }),
      "0 adjoints for 1 interfaces"));
  InterfaceAdjoint short_adjoint;
  short_adjoint.vertices.assign(2, Vec3::Ones());
  EXPECT_TRUE(contains(error_of([&] {
                         accumulate_interface_gradient(structure, options, {short_adjoint},
                                                       gradient);
                       }),
                       "adjoint 1 has 2 vertices, its interface 4"));
  std::vector<std::vector<Vec3>> short_gradient = {std::vector<Vec3>(8, Vec3::Zero())};
  EXPECT_TRUE(contains(error_of([&] {
                         accumulate_interface_gradient(structure, options, {InterfaceAdjoint{}},
                                                       short_gradient);
                       }),
                       "gradient has 1 blocks, the structure 2"));
}
