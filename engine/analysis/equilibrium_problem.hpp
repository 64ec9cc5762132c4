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
// Cables (Shin 2014, "Extension to tension elements") pull their two end
// bodies towards each other with t_k - k_k along their axis: tension t_k is
// free (up to max_tension), compression k_k is penalised like s_k. Their
// weight hangs half at each end. An end away from any block is a junction:
// a body of its own with force balance only. Axial forces alone may not
// balance a block (figure 1), so every block with a cable end gets virtual
// torques about its centroid, and every junction virtual forces, each p - n
// with p, n >= 0 penalised like tension: the penalty stays finite.
//
// Scaling: forces are in units of the mean weight per analysed body Wm
// (blocks' and cables' weight / analysed blocks and junctions) and lengths in
// units of the mean free-block size L (block_size), so the QP is the same in millimetres
// or kilometres and its numbers are O(1) per block whatever the model size.
// The objective is
//     sum_k [ s_k + tension_weight/2 s_k^2 + force_weight/(2n) (c_k^2 + f_uk^2 + f_vk^2) ]
// (likewise k_k, p_k, n_k penalised, t_k regularised) with n the number of
// bodies analysed. The linear tension term is an exact penalty: when a
// compression-only equilibrium exists, the optimum has no tension at all
// (the tiny force_weight regularisation only picks the most even force
// distribution).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/types.hpp"
#include "structure/structure.hpp"

namespace ashlar {

enum class FrictionModel {
  pyramid,  // inscribed pyramid, friction_sides sides, one edge along u (safe side)
  box,      // |f_u| <= mu c and |f_v| <= mu c (the thesis; up to sqrt 2 too generous)
};
inline constexpr EnumNames<FrictionModel, 2> kFrictionModelNames{
    {{{FrictionModel::pyramid, "pyramid"}, {FrictionModel::box, "box"}}}};

// How friction is bounded at a contact vertex.
enum class FrictionLaw {
  coulomb,  // by mu times the vertex's compression (associative: the rigid-block equilibrium)
  // By the vertex's shear strength, the group's `bound` (scaled), which the
  // kinematic method (kinematic.hpp) sets to mu times the compression found
  // before: friction that does not create the normal force it needs (no
  // dilatancy). Joints then carry no tension: the tension unknown acts on
  // no block and only buys friction beyond the strength, dearly. What the
  // joints cannot carry, virtual forces and torques on every free block
  // (slack groups) do, at the cost of the kinetic energy of the motion it
  // would start (Gauss's principle of least constraint): the QP is then one
  // step of frictional contact dynamics from rest.
  given_strength,
};

struct EquilibriumOptions {
  double friction = 0.7;            // Coulomb coefficient mu >= 0; +infinity: no sliding
  int friction_sides = 4;           // sides of the friction pyramid, >= 3
  FrictionModel friction_model = FrictionModel::pyramid;
  FrictionLaw friction_law = FrictionLaw::coulomb;
  double tension_weight = 1.0;      // quadratic tension penalty (scaled units)
  double force_weight = 1e-4;       // regularisation of compression and friction (over n)
  ContactOptions contact;           // how interfaces are found
};

// What a group of four unknowns x_k stands for.
enum class GroupKind {
  contact_vertex,  // (c, s, f_u, f_v) at one vertex of a contact polygon
  cable,           // (t, k, -, -): a cable's tension t and penalised compression k
  bounded_cable,   // the same, with t <= the cable's max_tension
  slack,           // (p, n, -, -): a virtual torque (or, at a junction, force) p - n, penalised
  weight,          // (w, -, -, -): a block's unknown weight w >= 0 (necessary weights, eq. 8)
};
constexpr int kGroupKinds = 5;

// Inequalities and objective shared by every group of one kind: row i
// gives r_i . x_k >= -bound_k * bound_coefficients(i) (bound_k: the
// group's ForceGroup::bound), or >= 0 when bound_coefficients is empty.
struct GroupRules {
  Eigen::Matrix<double, Eigen::Dynamic, 4> rows;
  Eigen::Vector4d hessian = Eigen::Vector4d::Zero();  // diagonal, scaled
  Eigen::Vector4d linear = Eigen::Vector4d::Zero();   // scaled
  Eigen::VectorXd bound_coefficients;                 // empty, or one per row
  // The lower side of row i for a group with this bound.
  double lower(Eigen::Index i, double bound) const {
    return bound_coefficients.size() ? -bound * bound_coefficients(i) : 0.0;
  }
};

// One group of four unknowns and its effect on the balance rows of the (at
// most two) bodies it acts on. A body is a block or a cable junction.
struct ForceGroup {
  GroupKind kind = GroupKind::contact_vertex;
  // The interface (contact vertex), the cable (cables), the body (slack:
  // a block index, or block count + junction index), or the block (weight).
  int source = -1;
  // Contact: which of its interface's vertices it stands at
  // (EquilibriumProblem::vertex_position); slack: which of its body's
  // balance rows it relieves.
  int component = -1;
  int block_a = -1, block_b = -1;  // contact: the interface's blocks; cable: the end blocks
  int row_a = -1, row_b = -1;  // first of each body's balance rows, -1 for supports
  // Body a gets the opposite force at its own arm (a contact's two blocks,
  // a cable's two ends): its effect, on_a(), is -on_b with lever x (b's
  // force) added to its moments, lever = (arm at b - arm at a) / L, an arm
  // 0 at a junction (no moment rows). Derived, not stored: a second matrix
  // was 192 bytes a group, 200 MB on a 100,052-block vault. A group on
  // body a alone (slack, weight: row_b -1) keeps the negative of its effect
  // in on_b and lever 0 (set_alone_on_a).
  Vec3 lever = Vec3::Zero();
  double bound = 0.0;  // scaled: a bounded cable's max_tension; a contact vertex's shear strength (FrictionLaw)
  // Scaled effect of the four unknowns on the balance rows of body b: force,
  // then moment about the block's centroid / L. Only the first block_rows
  // rows count: for planar problems they are Fx, Fz, My (balance_rows).
  // Last, after 64 bytes of the rest: a group is 256 bytes, four cache
  // lines (288 with a stored position: 37 MB more on a 100,052-block
  // vault).
  Eigen::Matrix<double, 6, 4> on_b = Eigen::Matrix<double, 6, 4>::Zero();

  // Adds to `out` the first D rows (D = block_rows: 6, or 3 planar) of
  // body a's effect T at_b of what has the effect `at_b` on body b (an
  // effect vector or column; group_reaction below applies T^T), entry by
  // entry: built as an Eigen vector and read back whole, the cross
  // product's scalar stores stalled the loads that followed (perf, the
  // imperfect dome's load capacity: add_group_effect 1,988 samples against
  // 1,235 with a stored on_a; 857 written so).
  template <int D, typename In, typename Out>
  void add_effect_at_a(const In& at_b, Out&& out) const {
    if constexpr (D == 6) {
      const double fx = at_b(0), fy = at_b(1), fz = at_b(2);
      out(0) -= fx;
      out(1) -= fy;
      out(2) -= fz;
      out(3) += lever.y() * fz - lever.z() * fy - at_b(3);
      out(4) += lever.z() * fx - lever.x() * fz - at_b(4);
      out(5) += lever.x() * fy - lever.y() * fx - at_b(5);
    } else {  // My += (lever x F)_y
      out(0) -= at_b(0);
      out(1) -= at_b(1);
      out(2) += lever.z() * at_b(0) - lever.x() * at_b(1) - at_b(2);
    }
  }
  // All six rows of body a's effect, in the order of a problem with `block_rows` rows.
  Eigen::Matrix<double, 6, 4> on_a(int block_rows) const;
  // Entry (row, column) of body a's effect, for a group on a alone.
  void set_alone_on_a(int row, int column, double value) { on_b(row, column) = -value; }
};

// add_effect and reaction of EquilibriumProblem for D = block_rows balance
// rows known at compile time (the solver's loops run them millions of
// times).
template <int D>
void add_group_effect(const ForceGroup& v, const Eigen::Vector4d& forces, Eigen::VectorXd& rows) {
  const Eigen::Matrix<double, D, 1> at_b = v.on_b.topRows<D>() * forces;
  if (v.row_a >= 0) v.add_effect_at_a<D>(at_b, rows.segment<D>(v.row_a));
  if (v.row_b >= 0) rows.segment<D>(v.row_b) += at_b;
}

// on_b^T m_b + on_a^T m_a, with on_a^T m_a = on_b^T (-m_a) plus, through
// the lever, on_b's force rows times m_a's moments x lever.
template <int D>
Eigen::Vector4d group_reaction(const ForceGroup& v, const Eigen::VectorXd& multipliers) {
  Eigen::Matrix<double, D, 1> m_b = Eigen::Matrix<double, D, 1>::Zero();
  if (v.row_b >= 0) m_b = multipliers.segment<D>(v.row_b);
  if (v.row_a >= 0) m_b -= multipliers.segment<D>(v.row_a);
  Eigen::Vector4d out = v.on_b.topRows<D>().transpose() * m_b;
  if (v.row_a >= 0) {
    const auto m = multipliers.segment<D>(v.row_a);
    if constexpr (D == 6) {
      const Vec3& l = v.lever;
      out.noalias() += v.on_b.row(0).transpose() * (m(4) * l.z() - m(5) * l.y()) +
                       v.on_b.row(1).transpose() * (m(5) * l.x() - m(3) * l.z()) +
                       v.on_b.row(2).transpose() * (m(3) * l.y() - m(4) * l.x());
    } else {
      out.noalias() += v.on_b.row(0).transpose() * (v.lever.z() * m(2)) - v.on_b.row(1).transpose() * (v.lever.x() * m(2));
    }
  }
  return out;
}

// An equilibrium problem but for its force groups: the bodies and their
// balance rows, the loads, the groups' rules and the units. Apart, so that
// a problem with other groups (TwinGroups::merge) copies this alone.
struct ProblemFrame {
  // The interfaces the contact vertices stand on (ForceGroup::source).
  std::shared_ptr<const std::vector<Interface>> interfaces;
  std::vector<int> row_of_block;        // first balance row per block, -1 if none
  std::vector<Vec3> junctions;          // m: where cable ends meet away from blocks
  std::vector<int> row_of_junction;     // first balance row per junction, -1 if none
  std::vector<int> floating_blocks;     // free blocks with no path of contacts or cables to a support
  std::vector<int> floating_junctions;
  int block_rows = 6;                   // balance rows per body: 6, or 3 for planar structures
  int row_count = 0;                    // block_rows per analysed body
  Eigen::VectorXd rhs;                  // balance: sum of group effects = rhs
  std::array<GroupRules, kGroupKinds> rules;  // indexed by GroupKind
  double weight_unit = 1.0;          // N: one scaled force unit (mean weight per analysed body)
  double length_unit = 1.0;          // m: one scaled length unit
  double total_weight = 0.0;         // N: weight carried by the analysed bodies
  int body_count = 0;                // analysed blocks and junctions
};

struct EquilibriumProblem : ProblemFrame {
  // Contact vertices first (in interface order), then cables, then slacks.
  std::vector<ForceGroup> groups;
  int contact_vertex_count = 0;

  // Where contact vertex `v` stands, m.
  const Vec3& vertex_position(const ForceGroup& v) const { return (*interfaces)[v.source].vertices[v.component]; }
  const GroupRules& rules_of(const ForceGroup& group) const {
    return rules[static_cast<int>(group.kind)];
  }
  int variable_count() const { return 4 * static_cast<int>(groups.size()); }
  // Whether some body has no path to a support: then no forces balance it.
  bool has_floating_bodies() const { return !floating_blocks.empty() || !floating_junctions.empty(); }
  // rows += A_k forces: the effect of group k's unknowns on the balance rows.
  void add_effect(const ForceGroup& v, const Eigen::Vector4d& forces,
                  Eigen::VectorXd& rows) const {
    if (block_rows == 3) add_group_effect<3>(v, forces, rows);
    else add_group_effect<6>(v, forces, rows);
  }
  // A_k^T multipliers: what the balance rows' multipliers say to group k.
  Eigen::Vector4d reaction(const ForceGroup& v, const Eigen::VectorXd& multipliers) const {
    return block_rows == 3 ? group_reaction<3>(v, multipliers) : group_reaction<6>(v, multipliers);
  }
  // Where each group's inequality rows start in the stacked inequalities
  // (the solver's slacks w and multipliers z); one more entry: the total.
  std::vector<int> inequality_starts() const {
    std::vector<int> starts(groups.size() + 1, 0);
    for (size_t k = 0; k < groups.size(); ++k) {
      starts[k + 1] = starts[k] + static_cast<int>(rules_of(groups[k]).rows.rows());
    }
    return starts;
  }
  // Position of the vertical force (Fz) among a body's balance rows, where
  // its weight enters: 2, or 1 for planar problems.
  int vertical_row() const;
  // Whether the forces are the contacts' alone: no cables and no
  // junctions (slack groups, the virtual torques, may be there). The
  // linear programs built from such a problem by dropping the slacks
  // (load capacity's largest multiple, friction demand's borrowing) have
  // every force bounded by its friction rows.
  bool contacts_only() const;
  // The equality constraint matrix (row_count x variable_count), for export
  // and residual checks; the solver works with the per-group blocks.
  Eigen::SparseMatrix<double> equality_matrix() const;
};

// Builds the problem. Throws InvalidArgument for bad options (naming them),
// for a planar structure with a load or cable out of its plane, and for a
// cable end attached to nothing (no block, and no other cable end there).
EquilibriumProblem build_equilibrium_problem(const Structure& structure,
                                             const EquilibriumOptions& options);

// The balance rows' right-hand side (scaled, row_count long, as
// problem.rhs) of `structure`'s loads: its blocks' weights, point loads and
// cables' weights, in `problem`'s units (weight_unit, length_unit) and rows.
// For a structure with the blocks, supports, contacts and cables `problem`
// was built for, loaded otherwise; with only its point loads changed it is
// the rhs build_equilibrium_problem gives, to the bit. Throws
// InvalidArgument for another number of blocks or cable junctions, and as
// build_equilibrium_problem for a planar structure loaded out of its plane.
Eigen::VectorXd load_rhs(const Structure& structure, const EquilibriumProblem& problem);

// How far the scaled unknowns x, with every penalised unknown (tension,
// cable compression, virtual torques) set to zero, are from a
// compression-only equilibrium that respects friction: the largest
// imbalance of a body relative to its own load (or the mean body weight
// when larger), or of a bound (unit rows: a force) relative to the mean body
// weight. Small (below AnalysisSettings::stable_tolerance, equilibrium.hpp)
// means x certifies stability, whatever the solver's status.
double compression_only_imbalance(const EquilibriumProblem& problem, const Eigen::VectorXd& x);


// The balance rows a problem keeps, in order, as indices into (Fx, Fy, Fz,
// Mx, My, Mz): all six, or for a planar structure (x-z plane) Fx, Fz, My
// first.
const std::array<int, 6>& balance_rows(bool planar);

// Columns (c, s, f_u, f_v) of the balance rows of block b, with centroid
// `centroid` (m), for a contact force acting on it at `position` (m), in
// the frame of `contact` (block a's: ForceGroup::on_a); moments about the
// centroid divided by `length_unit` (m); rows in the order `rows`.
Eigen::Matrix<double, 6, 4> contact_vertex_effect(const Interface& contact, const Vec3& position,
                                                  const Vec3& centroid, double length_unit,
                                                  const std::array<int, 6>& rows);

// The right-hand side of a body's six balance rows (Fx, Fy, Fz, Mx, My, Mz,
// scaled) for a force `force` (N) applied at `at` (m): moments about
// `centroid` over length_unit (m), none when centroid is null (a junction).
Eigen::Matrix<double, 6, 1> applied_force_rhs(const Vec3& force, const Vec3& at,
                                              const Vec3* centroid, double weight_unit,
                                              double length_unit);

// The friction rows (over c, f_u, f_v) for the options, each of unit length
// (rows . (c, f_u, f_v) >= 0); empty for mu = inf.
Eigen::Matrix<double, Eigen::Dynamic, 3> friction_rows(const EquilibriumOptions& options);

}  // namespace ashlar
