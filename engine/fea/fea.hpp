// Linear-elastic finite-element analysis of a block structure with contact
// constraints (the thesis's equation 9).
//
//   minimise   1/2 u^T K u - f^T u
//   subject to  T u = 0,  N u >= 0,  and (N u)_i lambda_i = 0
//
// u: nodal displacements (m); K: block stiffness, assembled per block (no
// stiffness couples two blocks); f: consistent gravity and point loads (N).
// Each contact node is tied to the point it touches on the other block (the
// trilinear interpolation of that block's nodes; a node of the other block
// when meshes match), or to zero on a support. Its relative displacement
// has a normal part N u (the opening) and a tangential part T u.
//
// Unilateral contact (the default) solves the problem as written: a node
// may open, never overlap, and carries compression only while closed; the
// tangential part stays tied (unlimited friction: with small displacements
// a hinge opens along the normal, so the ties block sliding, not hinging).
// This convex program is the dual of the equilibrium method with unlimited
// friction (Shin et al. 2016): it has a bounded solution exactly when a
// compression-only equilibrium exists. A primal-dual active-set iteration
// solves it: nodes in tension open, open nodes that overlap close again;
// where that cycles, an interior-point method (contact_program.hpp) finds
// the contact state and the iteration resumes from it.
//
// Relaxation is the thesis's algorithm: solve with every node tied in all
// three directions, release those in tension (both ways), solve again; a
// released node never comes back.
//
// Each solve has equality ties only; it is solved in augmented-Lagrangian
// form: K + rho A^T A is symmetric positive definite whenever the ties hold
// every block, so CHOLMOD factorises it (pattern analysed once, refactorised
// when the ties change), and the multipliers are iterated to A u = 0 with
// that one factorisation. The multipliers are the contact forces.
#pragma once

#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "core/types.hpp"
#include "fea/fea_mesh.hpp"
#include "fea/hex_element.hpp"
#include "structure/contact_detection.hpp"
#include "structure/structure.hpp"

namespace ashlar {

enum class FeaContactModel {
  Unilateral,  // nodes open and close until every closed one is in compression and no open one overlaps
  Relaxation,  // the thesis: release the nodes in tension, solve again; released nodes stay free
};
inline constexpr EnumNames<FeaContactModel, 2> kFeaContactModelNames{
    {{{FeaContactModel::Unilateral, "unilateral"}, {FeaContactModel::Relaxation, "relaxation"}}}};

// Which contact nodes in tension each relaxation step releases.
enum class FeaRelease {
  All,      // every one (the thesis's step 3)
  Largest,  // those of the interface carrying the most tension, and of any
            // within 1e-6 of it (symmetric structures stay symmetric)
};
inline constexpr EnumNames<FeaRelease, 2> kFeaReleaseNames{{{{FeaRelease::All, "all"}, {FeaRelease::Largest, "largest"}}}};

struct FeaSettings {
  Elasticity material;           // Young's modulus 20 GPa, Poisson 0.2
  FeaContactModel method = FeaContactModel::Unilateral;
  // false: one solve with every node tied (the thesis's step 1), status
  // Tension when any node pulls.
  bool relax = true;
  // Solves after the first at most: active-set updates (unilateral) or
  // releases (relaxation). The unilateral iteration needs 2-15 on the model
  // library; relaxation with Largest one per hinge-forming interface
  // (30-190 on walls with openings).
  int max_relax_iterations = 200;
  // Relaxation only. All follows the thesis. On coarse meshes of many voussoirs several
  // neighbouring crown joints start in tension; releasing them together
  // leaves nearly collinear hinges and the arch becomes a mechanism, where
  // Largest opens one hinge at a time.
  FeaRelease release = FeaRelease::All;
  // Relaxation and tied solves: a contact node is in tension when its normal force is below
  // -tension_tolerance * (total weight of the free blocks) / (contact
  // nodes): solver round-off on a node that carries nothing is not tension.
  double tension_tolerance = 1e-6;
  // A displacement larger than this fraction of the structure's
  // bounding-box diagonal ends the analysis with status Mechanism: the
  // ties no longer hold every block (or the material is so soft that
  // small-displacement elasticity does not apply).
  double max_displacement = 0.01;
  bool stresses = false;          // per-element stress at the element centre
  ContactOptions contact;         // how interfaces are found
};

enum class FeaStatus {
  CompressionOnly,  // every closed contact node in compression (and, unilateral, no open one overlaps)
  Tension,          // relax off, and a node pulls
  Mechanism,        // the closed ties do not hold every block: no compression-only equilibrium
  IterationLimit,   // max_relax_iterations solves without a consistent contact state: no verdict
  Interrupted,      // Ctrl-C, SIGTERM or a sandbox deadline: no verdict
};
inline constexpr EnumNames<FeaStatus, 5> kFeaStatusNames{{{{FeaStatus::CompressionOnly, "compression_only"},
                                                           {FeaStatus::Tension, "tension"},
                                                           {FeaStatus::Mechanism, "mechanism"},
                                                           {FeaStatus::IterationLimit, "iteration_limit"},
                                                           {FeaStatus::Interrupted, "interrupted"}}}};
const char* fea_status_name(FeaStatus status);

// One tied contact node.
struct FeaContact {
  int interface = -1;    // 0-based, into structure.interfaces(settings.contact)
  int node = -1;         // the tied mesh node
  int block = -1;        // its block
  NodeWeights target;    // the point it touches (empty on a support)
  Vec3 force_on_b = Vec3::Zero();  // N, the force that block a applies to block b here
  double normal_force = 0.0;       // N, force_on_b . normal: > 0 compression
  // m, separation from the point it touches along the interface normal
  // (negative: overlap); zero to round-off while tied. A released node that
  // opens shows the hinge.
  double opening = 0.0;
  bool tensile = false;            // in tension after the last solve (closed ties only)
  // Open at the end: normal force zero (relaxation: the whole force).
  bool released = false;
  int released_at = 0;             // the iteration that last opened it (1-based)
};

// The contacts of one interface, summed.
struct FeaInterfaceForce {
  double compression = 0.0;  // N, sum of positive normal forces
  double tension = 0.0;      // N, sum of the magnitudes of negative ones
  Vec3 resultant = Vec3::Zero();  // N, total force on block b
  Vec3 center_of_pressure = Vec3::Zero();  // normal-force-weighted position (m); interface centre when none
  int contacts = 0, released = 0;
};

struct FeaIteration {
  int active = 0;          // contact nodes closed in this solve
  int tensile = 0;         // of them, in tension after it
  int released = 0, engaged = 0;  // nodes opened and closed after it
  double tension = 0.0;    // N, their total tensile normal force
  double max_tension = 0.0;  // N, the largest
  int multiplier_steps = 0;  // augmented-Lagrangian updates to reach A u = 0
  double constraint_error = 0.0;  // m, max |A u| at the end
  double seconds = 0.0;
};

struct FeaResult {
  FeaStatus status = FeaStatus::Tension;
  bool compression_only = false;
  int iterations = 0;  // solves after the first
  // Unilateral contact: iterations of the interior-point program, when the
  // active-set iteration handed over to it (0: it did not).
  int interior_point_iterations = 0;
  std::vector<FeaIteration> history;  // one per solve
  std::vector<Vec3> displacements;    // per mesh node (m)
  std::vector<FeaContact> contacts;
  std::vector<FeaInterfaceForce> interfaces;  // per structure interface
  std::vector<Stress> stresses;       // per element, when settings.stresses
  // NaN without a verdict (mechanism, iteration limit, interrupted): the
  // last solve is no equilibrium.
  double max_displacement = 0.0;      // m
  // Largest overlap of an open node into the block it touches (m): within
  // the overlap tolerance for unilateral contact; relaxation frees a
  // released node both ways, as in the thesis.
  double max_penetration = 0.0;
  double total_weight = 0.0;          // N, of the free blocks
  int dofs = 0;
  long factor_nonzeros = 0;
  double seconds = 0.0;
};

// Throws InvalidArgument for bad settings, structures with cables (not
// modelled), non-hexahedral free blocks; outcomes are statuses.
FeaResult analyze_fea(const Structure& structure, const FeaMesh& mesh, const FeaSettings& settings);

}  // namespace ashlar
