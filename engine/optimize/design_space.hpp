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
//  - Planar faces and kept normals are equations c(x0 + B z) = 0 (c_i is the
//    distance, in metres, of one face vertex, or of another block's vertex
//    lying on the face, from the plane of three face vertices, or from the
//    plane with the kept normal). They are nonlinear, and no
//    linear parameterisation keeps faces that share vertices planar, so they
//    are kept by a chart (PlanarChart): an exact, smooth map from z to the
//    constraint set. The chart projects z along the constraint normals of a
//    base design b, y = z + A_b^T lambda with c(y) = 0 (Newton), where A_b is
//    the constraint Jacobian at b (rows found redundant at b by a rank-
//    revealing sparse QR are dropped). By the implicit function theorem its
//    derivative is exact and cheap: for f(y(z)),
//        df/dz = g - A(y)^T mu,  (A_b A(y)^T) mu = A_b g,
//    one sparse LU solve. So both optimisers see a smooth function with an
//    exact gradient whose every evaluated design has planar faces to about
//    1e-12 of the face size; the chart is re-centred when the optimiser
//    restarts. A projection-after-each-step with a tangent-projected gradient
//    would be inexact off the constraint set and confuse L-BFGS's line search.
//  - Displacement bounds are box bounds on z (exact for points and vertices
//    whose basis is the identity or axis-aligned); a design whose planar-face
//    correction carries a coordinate past its bound is rejected, like one
//    with a block below the minimum volume. Rejected designs are never passed
//    to the objective; optimisers shorten their step instead.
// Everything is sparse and linear in the model size (spatial hashing for
// coincident positions, sparse QR and LU on the constraint Jacobian).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

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
  // position this close to another block's face (a T-junction, a block
  // standing inside a larger face, a cable anchor) stays in that face's
  // plane. So contacts between blocks stay closed. Default: 1e-9 x the
  // model size.
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

  // Number of reduced variables z (metres: displacement components).
  int variable_count() const { return variable_count_; }
  // z of the initial design made exactly planar (every face, kept normals);
  // it moves each position by about the input's planarity error at most.
  const Eigen::VectorXd& start() const { return start_; }
  // Box bounds on z: -/+ max_displacement (infinite by default).
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

  // The constraint equations c(x0 + B z) = 0 (m), one row per face vertex
  // beyond the three that fix a face's plane (one per vertex but the first
  // for kept normals) and per other position lying on the face; faces
  // shared by welded blocks count once.
  int constraint_count() const { return static_cast<int>(rows_.size()); }
  Eigen::VectorXd constraint_values(const Eigen::VectorXd& z) const;
  // d c / d z, constraint_count() x variable_count(), sparse.
  Eigen::SparseMatrix<double> constraint_jacobian(const Eigen::VectorXd& z) const;
  // Per row: the residual (m) below which the row counts as satisfied.
  const Eigen::VectorXd& constraint_tolerances() const { return tolerances_; }

private:
  // Welded positions: one shared initial position and displacement.
  struct Node {
    Vec3 initial = Vec3::Zero();    // m, mean of the welded positions
    int first_variable = 0;
    int variable_count = 0;         // 0 fixed, 2 on the mirror plane, 3 otherwise
    Mat3 basis = Mat3::Identity();  // displacement = basis.leftCols(count) * z[first..]
    PositionRef example;            // one of its positions, for messages
  };
  // Planarity: node i lies in the plane of nodes a, b, c (nodes = a, b, c, i).
  // Kept normal: node i lies in the plane through node a with `normal`
  // (nodes = a, i, -, -).
  struct ConstraintRow {
    std::array<int, 4> nodes{};
    bool keeps_normal = false;
    Vec3 normal = Vec3::Zero();
    double scale = 1.0;  // planarity: |(b - a) x (c - a)| at the start (m^2)
    FaceRef face;        // for messages
  };

  void check_input() const;
  void weld();
  void build_variables();
  void build_constraint_rows();
  void find_start();
  int position_index(const PositionRef& ref) const;
  std::vector<Vec3> node_positions(const Eigen::VectorXd& z) const;
  double row_value(const ConstraintRow& row, const std::vector<Vec3>& positions,
                   std::array<Vec3, 4>* gradient) const;

  std::vector<std::vector<FaceLoop>> faces_;
  DesignPoint initial_;
  DesignConstraints constraints_;
  double model_size_ = 1.0;
  double weld_tolerance_ = 0.0;
  std::vector<int> block_offset_;  // first position index of each block; points follow
  std::vector<int> node_of_position_;
  std::vector<Node> nodes_;
  int variable_count_ = 0;
  std::vector<ConstraintRow> rows_;
  Eigen::VectorXd tolerances_;
  Eigen::VectorXd start_;
  // |c| at the start: zero but for faces whose vertices are all fixed.
  Eigen::VectorXd start_residuals_;
};

// A smooth map from reduced variables z onto the designs that satisfy the
// constraint equations, linearised at a base design (see the file comment).
// Cheap to copy; it refers to `space`, which must outlive it.
class PlanarChart {
public:
  // base: z of a design on (or within tolerance of) the constraint set.
  PlanarChart(const DesignSpace& space, const Eigen::VectorXd& base);

  // y = z + A_b^T lambda with c(y) = 0 to tolerance, found by Newton's
  // method from lambda = 0; std::nullopt when it does not converge (z too far
  // from the base for this chart).
  std::optional<Eigen::VectorXd> project(const Eigen::VectorXd& z) const;
  // The derivative with respect to z of f(project(z)), given y = project(z)
  // and gradient = df/dy (size variable_count()). Throws GeometryError when
  // the constraints are singular at y.
  Eigen::VectorXd pull_back(const Eigen::VectorXd& y, const Eigen::VectorXd& gradient) const;
  // Number of independent constraint rows kept at the base.
  int rank() const { return static_cast<int>(rows_.size()); }

private:
  Eigen::SparseMatrix<double> jacobian(const Eigen::VectorXd& z) const;

  const DesignSpace* space_;
  std::vector<int> rows_;                      // independent rows at the base
  Eigen::SparseMatrix<double> selection_;      // rows_ x constraint_count()
  Eigen::SparseMatrix<double> base_jacobian_;  // A_b: rows_ x variable_count()
  Eigen::VectorXd tolerances_;                 // of rows_
};

}  // namespace ashlar
