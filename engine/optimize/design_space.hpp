// The design space of a geometry optimisation: which positions (block
// vertices and free points such as cable ends) may move, how they move
// together, and the nonlinear conditions every design must meet (planar
// faces, kept face normals, displacement bounds, minimum block volume).
//
// How the constraints are kept, and why:
//  - Linear ties become reduced variables: x = x0 + B z. Positions that
//    coincide (welding), user "move together" groups and mirror partners
//    share one displacement; fixed positions get none; positions on the
//    mirror plane move within it. B is never formed: each welded node keeps
//    its first variable and a 3x3 basis (identity, the mirror reflection, or
//    two in-plane axes), so x = x0 + B z and B^T g cost O(model size).
//  - Planes are variables too. Faces that must share a plane form a group:
//    a face, the faces of welded blocks with three non-collinear positions
//    in common with it (contacts, faces split by T-junctions), and coplanar
//    faces whose equations are dependent at the start (a flat strip of faces
//    held at both ends, such as an arch's side between fixed blocks, whose
//    equations are singular where staying flat and folding meet: it stays
//    flat). Every position on a group's faces, including other blocks'
//    vertices inside them or on their outline when in contact, gives one
//    equation: its distance from the group's plane,
//        c_i = n(z) . (x_i - center) - offset(z) = 0 (m),
//    with the normal tilted by two variables (none for a kept normal, one
//    for a plane the mirror maps onto itself) and the offset one more.
//    Explicit planes keep the equations local, well conditioned (chains of
//    four-point coplanarity conditions across overlapping faces are not) and
//    independent but for rare cases: a plane that fixed positions or
//    symmetry determine has no variables, a mirrored group no equations.
//  - The equations are nonlinear (tilt times position), so a chart
//    (PlanarChart) maps z exactly and smoothly onto the constraint set: it
//    moves z along the constraint normals of a base design b,
//        y = z + A_b^T lambda  with  c(y) = 0,
//    A_b the constraint Jacobian at b without rows that are redundant there
//    (a sparse LDL^T of A_b A_b^T finds any left). By the implicit function
//    theorem the gradient of f(y(z)) is exact and cheap:
//        df/dz = g - A(y)^T mu,  (A_b A(y)^T) mu = A_b g.
//    Newton's method for the projection and the system for mu are solved by
//    BiCGSTAB preconditioned with the one factor of A_b A_b^T per chart. So
//    the optimisers see a smooth function with an exact gradient, and every
//    design they evaluate has planar faces to about 1e-12 of their size.
//    Projecting after each step with a tangent-projected gradient instead
//    would be inexact off the constraint set and mislead L-BFGS's line
//    search. Charts are re-centred at the current design when an optimiser
//    restarts (gradient descent: every step).
//  - Displacement bounds are box bounds on z (per coordinate for positions
//    whose basis is the identity or axis-aligned); a design whose planar-face
//    correction carries a coordinate past its bound is rejected, like one
//    with a block below the minimum volume. Rejected designs are never passed
//    to the objective; optimisers shorten their step instead.
// Everything is sparse and linear in the model size but for the sparse
// factorisation (spatial hashing for coincident positions and positions on
// faces, one sparse LDL^T per chart).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

// A design counts as planar when no constraint row exceeds this many row
// tolerances (DesignSpace::constraint_tolerances).
constexpr double kRowSlack = 100.0;

// A design: every block vertex and every free point, in metres.
// block_vertices[b][k] is vertex k of block b; points[p] is free point p.
struct DesignPoint {
  std::vector<std::vector<Vec3>> block_vertices;
  std::vector<Vec3> points;
};

// One position of a design: vertex `index` of block `block`, or free point
// `index` when block is kFreePoint. Indices are 0-based; error messages count
// from 1, as the Lua API does.
struct PositionRef {
  static constexpr int kFreePoint = -1;
  int block = kFreePoint;
  int index = 0;

  static PositionRef vertex(int block, int index) { return {block, index}; }
  static PositionRef point(int index) { return {kFreePoint, index}; }
};

// Face `face` (0-based, in the block's face list) of block `block`.
struct FaceRef {
  int block = 0;
  int face = 0;
};

// The plane through `point` with normal `normal` (any non-zero length).
struct MirrorPlane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitX();
};

struct DesignConstraints {
  // Positions closer than this (m) are welded: they move together. A
  // position this close to the inside of another block's face (a block
  // standing inside a larger face, a cable anchor), or to its outline when
  // it is a vertex of a face in contact with it (a T-junction), stays in
  // that face's plane. So contacts between blocks stay closed. Default:
  // 1e-9 x the model size.
  std::optional<double> weld_tolerance;
  // Blocks that never move (e.g. supports); anything welded to them is fixed.
  std::vector<int> fixed_blocks;
  // Single block vertices or free points that never move.
  std::vector<PositionRef> fixed;
  // Each list shares one displacement.
  std::vector<std::vector<PositionRef>> move_together;
  // Mirror symmetry: displacements of mirror partners are mirror images,
  // positions on the plane move within it. Every movable position needs a
  // partner (within the weld tolerance). Default: none.
  std::optional<MirrorPlane> mirror;
  // Faces that keep their initial normal (e.g. a walkway stays horizontal).
  // Every face of every block stays planar regardless.
  std::vector<FaceRef> keep_normal;
  // Largest displacement of any coordinate from its initial value (m).
  double max_displacement = std::numeric_limits<double>::infinity();
  // Smallest allowed block volume (m^3); 0: any positive volume.
  double min_block_volume = 0.0;
};

class DesignSpace {
public:
  // faces[b]: the face loops of block b (0-based vertex indices, outward
  // orientation, as in Block). initial: the starting design, with as many
  // blocks as faces and every face index in range. Throws InvalidArgument,
  // naming the offending item, for malformed input or constraints (an index
  // out of range, a non-finite or negative setting, a movable position
  // without a mirror partner, two vertices of one block welded together, a
  // start below min_block_volume).
  DesignSpace(std::vector<std::vector<FaceLoop>> faces, DesignPoint initial,
              DesignConstraints constraints = {});

  const std::vector<std::vector<FaceLoop>>& faces() const { return faces_; }
  const DesignPoint& initial() const { return initial_; }
  const DesignConstraints& constraints() const { return constraints_; }
  // Diagonal of the bounding box of all positions (m); 1 for a lone point.
  double model_size() const { return model_size_; }

  // Number of reduced variables z (m): displacement components of the
  // movable positions, then the variables of the planes that faces lie in.
  int variable_count() const { return variable_count_; }
  int position_variable_count() const { return position_variable_count_; }
  // z of the initial design made exactly planar (every face, kept normals);
  // it moves each position by about the input's planarity error at most.
  const Eigen::VectorXd& start() const { return start_; }
  // Box bounds on z: -/+ max_displacement (infinite by default) for
  // positions, infinite for planes.
  Eigen::VectorXd lower_bounds() const;
  Eigen::VectorXd upper_bounds() const;

  // The design x0 + B z (no projection onto planar faces: see PlanarChart).
  DesignPoint design(const Eigen::VectorXd& z) const;
  // B^T gradient: the derivative with respect to z of a function whose
  // derivative with respect to every position is `gradient` (same shape as
  // the design, e.g. 1/m). Throws InvalidArgument when the shape differs.
  Eigen::VectorXd reduce(const DesignPoint& gradient) const;
  // Largest distance any position moves between designs z_from and z_to (m).
  double largest_move(const Eigen::VectorXd& z_from, const Eigen::VectorXd& z_to) const;

  // Why the design at z (already on the constraint set) is not admissible:
  // a coordinate beyond max_displacement, a face that is not planar, a block
  // below min_block_volume or inverted. Empty when it is admissible.
  std::string rejection(const Eigen::VectorXd& z) const;

  // The constraint equations c(z) = 0 (m): one row per position on a plane
  // (face vertices, positions of other blocks lying on the face), its
  // distance from the plane; see PlaneGroup.
  int constraint_count() const { return static_cast<int>(rows_.size()); }
  Eigen::VectorXd constraint_values(const Eigen::VectorXd& z) const;
  // d c / d z, constraint_count() x variable_count(), sparse.
  Eigen::SparseMatrix<double> constraint_jacobian(const Eigen::VectorXd& z) const;
  // Per row: the residual (m) below which the row counts as satisfied.
  const Eigen::VectorXd& constraint_tolerances() const { return tolerances_; }

private:
  // Welded positions: one shared initial position and displacement.
  struct Node {
    Vec3 initial = Vec3::Zero();  // m, mean of the welded positions
    int first_variable = 0;
    int variable_count = 0;         // 0 fixed, 2 on the mirror plane, 3 otherwise
    Mat3 basis = Mat3::Identity();  // displacement = basis.leftCols(count) * z[first..]
    PositionRef example;            // one of its positions, for messages
  };
  // Faces that share one plane (see the file comment) and the nodes lying
  // on them.
  struct PlaneGroup {
    std::vector<int> nodes;       // sorted
    FaceRef face;                 // its widest face (or the kept-normal one), for messages
    Vec3 center = Vec3::Zero();   // m, at the start
    Vec3 normal = Vec3::UnitZ();  // unit, at the start
    double size = 1.0;            // m, farthest node from the center
    // Plane variables (none when fixed nodes or symmetry fix the plane):
    // tilts z[first + k] (m at distance `size`) along tilts.col(k), then
    // the offset (m) along the normal.
    bool moves = false;
    int first_variable = 0;
    int tilt_count = 0;
    Mat3 tilts = Mat3::Zero();
    int source = 0;  // the face named by `face`, in FaceSet order
  };
  struct FaceSet;
  // Node `node` lies in the plane of group `group`.
  struct ConstraintRow {
    int group = 0;
    int node = 0;
  };

  void check_input() const;
  void weld();
  void build_variables();
  void build_plane_groups();
  // Groups the faces of equal root, then assigns plane variables and rows.
  void form_groups(const FaceSet& set, const std::vector<int>& root);
  void assign_plane_variables(const std::vector<char>& keeps_normal);
  // Pairs of faces (FaceSet order) of coplanar groups whose equations are
  // dependent at the start.
  std::vector<std::pair<int, int>> dependent_coplanar_faces() const;
  void find_start();
  int position_index(const PositionRef& ref) const;
  bool spans_plane(const std::vector<int>& nodes) const;
  std::vector<Vec3> node_positions(const Eigen::VectorXd& z) const;
  // The group's plane at z: normal . (x - center) = offset, the normal not
  // of unit length once tilted.
  std::pair<Vec3, double> plane_at(const PlaneGroup& plane, const Eigen::VectorXd& z) const;

  std::vector<std::vector<FaceLoop>> faces_;
  DesignPoint initial_;
  DesignConstraints constraints_;
  double model_size_ = 1.0;
  double weld_tolerance_ = 0.0;
  std::vector<int> block_offset_;  // first position index of each block; points follow
  std::vector<int> node_of_position_;
  std::vector<Node> nodes_;
  std::vector<int> partner_;  // mirror image of each node (-1: none, or no mirror)
  int position_variable_count_ = 0;
  int variable_count_ = 0;
  std::vector<PlaneGroup> groups_;
  std::vector<ConstraintRow> rows_;
  Eigen::VectorXd tolerances_;
  Eigen::VectorXd start_;
  // |c| at the start: zero but for nodes that cannot reach a fixed plane.
  Eigen::VectorXd start_residuals_;
};

}  // namespace ashlar
