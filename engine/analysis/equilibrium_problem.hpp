// The rigid-block equilibrium problem (Shin 2014, eq. 1) as a convex QP with
// per-vertex structure, in scaled units.
//
// At every vertex k of every contact polygon between blocks a and b, the
// force that a exerts on b is
//     F_k = (c_k - s_k) n + f_uk u + f_vk v
// with compression c_k >= 0, tension s_k >= 0 and friction (f_uk, f_vk) in
// the interface frame. Every free block balances its weight, its point loads
// and the contact forces (6 rows: force, then moment about its centroid).
// Friction is bounded by mu * c_k: a pyramid inscribed in the Coulomb cone
// with `friction_sides` sides and one edge along u, or the box
// |f_u|, |f_v| <= mu c; none when mu is infinite.
//
// Scaling: forces are in units of the mean free-block weight Wm (total free
// weight / free blocks) and lengths in units of the mean free-block size L,
// so the QP is the same in millimetres or kilometres and its numbers are
// O(1) per block whatever the model size. The objective is
//     sum_k [ s_k + tension_weight/2 s_k^2 + force_weight/(2n) (c_k^2 + f_uk^2 + f_vk^2) ]
// with n the number of free blocks analysed.
// The linear tension term is an exact penalty: when a compression-only
// equilibrium exists, the optimum has no tension at all (the tiny
// force_weight regularisation only picks the most even force distribution).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "structure/structure.hpp"

namespace ashlar {

enum class FrictionModel {
  pyramid,  // inscribed pyramid, friction_sides sides, one edge along u (safe side)
  box,      // |f_u| <= mu c and |f_v| <= mu c (the thesis; up to sqrt 2 too generous)
};

struct EquilibriumOptions {
  double friction = 0.7;            // Coulomb coefficient mu >= 0; +infinity: no sliding
  int friction_sides = 4;           // sides of the friction pyramid, >= 3
  FrictionModel friction_model = FrictionModel::pyramid;
  double tension_weight = 1.0;      // quadratic tension penalty (scaled units)
  double force_weight = 1e-4;       // regularisation of compression and friction (over n)
  ContactOptions contact;           // how interfaces are found
};

// One contact vertex: the unknowns (c, s, f_u, f_v) at one polygon vertex.
struct ContactVertex {
  int interface_index = -1;  // into Structure::interfaces()
  int block_a = -1, block_b = -1;
  int row_a = -1, row_b = -1;  // first of the 6 balance rows, -1 for supports
  Vec3 position = Vec3::Zero();  // m
  // Scaled effect of (c, s, f_u, f_v) on the balance rows of block b and of
  // block a: force, then moment about the block's centroid / L. Only the
  // first block_rows rows count: for planar problems they are Fx, Fz, My.
  Eigen::Matrix<double, 6, 4> on_b, on_a;
};

struct EquilibriumProblem {
  std::vector<ContactVertex> vertices;  // 4 unknowns each: c, s, f_u, f_v
  std::vector<int> row_of_block;        // first balance row per block, -1 if none
  std::vector<int> floating_blocks;     // free blocks with no path of contacts to a support
  int block_rows = 6;                   // balance rows per block: 6, or 3 for planar structures
  int row_count = 0;                    // block_rows per analysed free block
  Eigen::VectorXd rhs;                  // balance: sum of contact effects = rhs
  // Inequality rows shared by every vertex, over (c, s, f_u, f_v): each row
  // r gives r . x_k >= 0. The first two are c >= 0 and s >= 0.
  Eigen::Matrix<double, Eigen::Dynamic, 4> vertex_rows;
  Eigen::Vector4d hessian_diagonal;  // per vertex, scaled
  Eigen::Vector4d linear;            // per vertex, scaled
  double weight_unit = 1.0;          // N: one scaled force unit (mean free-block weight)
  double length_unit = 1.0;          // m: one scaled length unit
  double total_weight = 0.0;         // N: weight of the free blocks analysed

  int variable_count() const { return 4 * static_cast<int>(vertices.size()); }
  // rows += A_k forces: the effect of vertex k's unknowns on the balance rows.
  void add_effect(const ContactVertex& v, const Eigen::Vector4d& forces,
                  Eigen::VectorXd& rows) const {
    const int d = block_rows;
    if (v.row_a >= 0) rows.segment(v.row_a, d).noalias() += v.on_a.topRows(d) * forces;
    if (v.row_b >= 0) rows.segment(v.row_b, d).noalias() += v.on_b.topRows(d) * forces;
  }
  // A_k^T multipliers: what the balance rows' multipliers say to vertex k.
  Eigen::Vector4d reaction(const ContactVertex& v, const Eigen::VectorXd& multipliers) const {
    const int d = block_rows;
    Eigen::Vector4d out = Eigen::Vector4d::Zero();
    if (v.row_a >= 0) out.noalias() += v.on_a.topRows(d).transpose() * multipliers.segment(v.row_a, d);
    if (v.row_b >= 0) out.noalias() += v.on_b.topRows(d).transpose() * multipliers.segment(v.row_b, d);
    return out;
  }
  // The equality constraint matrix (row_count x variable_count), for export
  // and residual checks; the solver works with the per-vertex blocks.
  Eigen::SparseMatrix<double> equality_matrix() const;
};

// Builds the problem. Throws InvalidArgument for bad options (naming them),
// and for a planar structure with a load out of its plane.
EquilibriumProblem build_equilibrium_problem(const Structure& structure,
                                             const EquilibriumOptions& options);

// The balance rows a problem keeps, in order, as indices into (Fx, Fy, Fz,
// Mx, My, Mz): all six, or for a planar structure (x-z plane) Fx, Fz, My
// first.
const std::array<int, 6>& balance_rows(bool planar);

// Columns (c, s, f_u, f_v) of the balance rows of a block with centroid
// `centroid` (m) for a contact force acting on it at `position` (m), in the
// frame of `contact`; sign +1 for block b, -1 for block a; moments about the
// centroid divided by `length_unit` (m); rows in the order `rows`.
Eigen::Matrix<double, 6, 4> contact_vertex_effect(const Interface& contact, const Vec3& position,
                                                  const Vec3& centroid, double length_unit,
                                                  double sign, const std::array<int, 6>& rows);

// The friction rows (over c, f_u, f_v) for the options; empty for mu = inf.
Eigen::Matrix<double, Eigen::Dynamic, 3> friction_rows(const EquilibriumOptions& options);

}  // namespace ashlar
