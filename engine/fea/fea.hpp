// Linear-elastic finite-element analysis of a block structure with contact
// constraints (the thesis's equation 9), and iterative constraint
// relaxation: release every contact node in tension and solve again, until
// the contacts are compression-only or the iteration limit.
//
//   minimise   1/2 u^T K u - f^T u   subject to  A u = 0
//
// u: nodal displacements (m); K: block stiffness, assembled per block (no
// stiffness couples two blocks); f: consistent gravity and point loads (N).
// Each row triple of A ties one contact node: its displacement equals that
// of the point it touches on the other block (the trilinear interpolation
// of that block's nodes; a node of the other block when meshes match), or
// zero on a support. The KKT system is solved in its augmented-Lagrangian
// form: K + rho A^T A is symmetric positive definite whenever the ties hold
// every block, so CHOLMOD factorises it (pattern analysed once, refactorised
// after each release), and the multipliers are iterated to A u = 0 with
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

// Which contact nodes in tension each relaxation step releases.
enum class FeaRelease {
  All,      // every one (the thesis's step 3)
  Largest,  // those of the interface carrying the most tension, and of any
            // within 1e-6 of it (symmetric structures stay symmetric)
};
inline constexpr EnumNames<FeaRelease, 2> kFeaReleaseNames{{{{FeaRelease::All, "all"}, {FeaRelease::Largest, "largest"}}}};

struct FeaSettings {
  Elasticity material;           // Young's modulus 20 GPa, Poisson 0.2
  bool relax = true;             // release nodes in tension and solve again
  int max_relax_iterations = 20;
  // All follows the thesis. On coarse meshes of many voussoirs several
  // neighbouring crown joints start in tension; releasing them together
  // leaves nearly collinear hinges and the arch becomes a mechanism, where
  // Largest opens one hinge at a time.
  FeaRelease release = FeaRelease::All;
  // A contact node is in tension when its normal force is below
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
  CompressionOnly,  // every active contact node in compression
  Tension,          // tension remains (relax off, or the iteration limit)
  Mechanism,        // the active ties do not hold every block
};
inline constexpr EnumNames<FeaStatus, 3> kFeaStatusNames{{{{FeaStatus::CompressionOnly, "compression_only"},
                                                           {FeaStatus::Tension, "tension"},
                                                           {FeaStatus::Mechanism, "mechanism"}}}};
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
  bool tensile = false;            // in tension after the last solve (active ties only)
  bool released = false;           // released by relaxation (force zero)
  int released_at = 0;             // the relaxation iteration that released it (1-based)
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
  int active = 0;          // contact nodes tied in this solve
  int tensile = 0;         // of them, in tension after it
  double tension = 0.0;    // N, their total tensile normal force
  double max_tension = 0.0;  // N, the largest
  int multiplier_steps = 0;  // augmented-Lagrangian updates to reach A u = 0
  double constraint_error = 0.0;  // m, max |A u| at the end
  double seconds = 0.0;
};

struct FeaResult {
  FeaStatus status = FeaStatus::Tension;
  bool compression_only = false;
  int iterations = 0;  // solves after the first (releases)
  std::vector<FeaIteration> history;  // one per solve
  std::vector<Vec3> displacements;    // per mesh node (m)
  std::vector<FeaContact> contacts;
  std::vector<FeaInterfaceForce> interfaces;  // per structure interface
  std::vector<Stress> stresses;       // per element, when settings.stresses
  // Of a mechanism both are NaN: its last solve is no equilibrium.
  double max_displacement = 0.0;      // m
  // Largest overlap of a released node into the block it had touched (m):
  // releases free the node both ways, as in the thesis.
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
