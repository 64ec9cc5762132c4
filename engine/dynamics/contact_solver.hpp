// One step's contact impulses: a projected Gauss-Seidel (non-smooth
// Gauss-Seidel, as in LMGC90's NSCD and Siconos' fc3d NSGS with a projection
// local solver) over contact points with unilateral contact and Coulomb
// friction, at velocity level.
//
// Unknowns: per contact point, the impulse P = (P_n, P_t) (N s) that body b
// receives (body a the opposite), in the contact's frame (n from a into b,
// two tangents). Per contact, with U the relative velocity of b's material
// point against a's after the step (m/s):
//   0 <= P_n  complementary to  U_n - target_n >= 0   (unilateral contact,
//     target_n = e * the approach speed before the step: Newton's impact law)
//   |P_t| <= mu P_n, and U_t = -lambda P_t, lambda >= 0, lambda (mu P_n - |P_t|) = 0
//     (Coulomb friction, no dilatancy).
// Rows between the same two bodies that follow one another form a group
// (the points of one contact), solved together by repeated passes before
// the next group. Sweeps visit the groups in order and back in turn
// (symmetric Gauss-Seidel; the caller orders them, e.g. from the top of a
// structure down, along its load path). A pass solves each row's normal
// impulse exactly (the others held) and moves its tangential impulse by a
// scalar step against the slip, projected on the disc |P_t| <= mu P_n: a
// fixed point of the sweep satisfies the laws above exactly. A row that
// breaks them by at most a tenth of the tolerance is left as it is, and a
// group whose rows all were, and whose bodies nothing has moved since, is
// not visited again until something does.
//
// Sweeps alone move a change of load through a structure one contact per
// sweep (a shaken wall took 230-290 sweeps a step). After the first sweep
// (when it has not solved the step) and every few sweeps after (unless
// the sweeps, at the rate their residual falls, are about to finish the
// step), a global step (PGS with subspace minimisation, as in
// Silcowitz, Niebe and Erleben 2010) solves the laws as equalities on
// the current active set at once: every pressed (or approaching) point
// keeps its normal velocity on target, every sticking
// one (a point at its friction limit that does not slip sticks) its slip
// at zero, sliding ones keep their friction. That linear system,
// W_S dP = r with W_S = J_S M^-1 J_S^T and r = target - U_S (singular: the
// corner points of one face are redundant), is regularised by a small
// compliance E, dP = E^-1 (r - J_S dv), and solved in the bodies'
// velocities, (M + J_S^T E^-1 J_S) dv = J_S^T E^-1 r, 6 unknowns per free
// body, by a sparse Cholesky factorisation (core/sparse_cholesky.hpp; a
// ContactSolver keeps its symbolic analysis from step to step while the
// same bodies touch), refined by two more solves on what is left of r
// (each on M dv of the one before: what is left is known without a pass
// over the rows).
// The impulses are projected on the cones; points the step left pulling
// are released and the step taken once more without them. Then the
// sweeps go on: they alone decide convergence, with the same residual
// test, so the answer's accuracy is the sweeps'. A solve stops taking
// global steps after three left the residual larger than before them.
//
// Threads: a solve of at least 2,000 rows is split over the solver's
// threads. The free bodies are cut into parts of about equal numbers of
// rows, never across the load path (the caller's order): slabs across a
// wall's length (runs of a breadth-first order of the bodies the rows
// link, from a far end), or across a tower's width (by the bodies'
// centroids, rebuilt from the rows' arms). Each sweep runs the parts' own groups
// at the same time, each part on its thread (two parts never write one
// body: a fixed body is never written), and the few groups that link two
// parts after them, forward, or before them, backward: the same sweep as
// one thread taking the groups part after part, so a split solve gives
// the same answer in every run with the same threads, and one within the
// tolerance of the unsplit order's. The global step's passes are split by
// rows (work of a row alone) or by parts (each part adds into its own
// bodies' entries of the matrix, the right-hand side and the velocities,
// in the rows' order): they give the same numbers as on one thread. One
// thread: the sweeps in the caller's order and the factorisation whole
// (sparse_cholesky.hpp's split over two cores is used only with more).
//
// Where the sweeps stall (the load cycling between the redundant corners
// of a face, or between points sliding at their friction limit, or a
// mechanism of many blocks sliding and rocking at once), an interior-point
// method on the step's whole problem (contact_interior.hpp) is taken every
// interior_after_sweeps sweeps; the sweeps after it judge its answer by
// the same test.
#pragma once

#include <memory>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

class ParallelLoop;

// The bodies' velocities and inverse masses; a fixed body has zero inverse
// mass and inertia and keeps zero velocity.
struct BodyVelocities {
  std::vector<Vec3> linear;        // m/s, of the centroid
  std::vector<Vec3> angular;       // rad/s, world frame
  std::vector<double> inverse_mass;    // 1/kg
  std::vector<Mat3> inverse_inertia;   // 1/(kg m^2), world frame, about the centroid
};

// One active contact point of the step.
struct ContactRow {
  int a = -1, b = -1;             // bodies; a pair of fixed bodies is never a row
  Vec3 arm_a = Vec3::Zero();      // contact point - a's centroid (m)
  Vec3 arm_b = Vec3::Zero();      // contact point - b's centroid (m)
  Mat3 frame = Mat3::Identity();  // rows: n (from a into b), t1, t2
  double friction = 0.0;          // mu, >= 0 (inf: no sliding)
  double target_normal = 0.0;     // least normal velocity after the step (m/s)
  Vec3 impulse = Vec3::Zero();    // (P_n, P_t1, P_t2), N s: the warm start in, the answer out
};

struct ContactSolverSettings {
  int max_sweeps = 1000;
  // Stop after a sweep in which no contact broke the laws above by more
  // than this (m/s), its relative velocity measured at the impulse the
  // sweep found it with: the normal velocity off its target where the
  // contact presses (or below it where it does not), the slip of a
  // sticking contact, the slip off the direction opposite the friction of
  // a sliding one.
  double velocity_tolerance = 1e-9;
  // Take global steps between the sweeps (see above); false: sweeps only.
  bool global_steps = true;
  // A solve that has not converged after this many sweeps (and after each
  // as many more) takes the interior-point method on its rows
  // (contact_interior.hpp) before sweeping on; 0: never.
  int interior_after_sweeps = 100;
};

struct ContactSolverReport {
  int sweeps = 0;
  bool converged = false;
  // The largest residual (m/s) of the last sweep, and the row it was met
  // at (index into rows; -1 when there are no rows).
  double residual = 0.0;
  int worst_row = -1;
  int global_steps = 0;     // global steps taken
  int factorizations = 0;   // numeric factorisations (one per global step)
  int interior_iterations = 0;  // interior-point iterations (one sparse Cholesky each)
};

// Solves rows of one step after another, keeping the global step's
// sparse pattern and its analysis between solves while the rows link the
// same bodies.
class ContactSolver {
public:
  // threads: the solves' threads (0: one per core; at most
  // ParallelLoop::kMaxThreads are used); 1: all on the caller's thread.
  explicit ContactSolver(int threads = 0);
  ~ContactSolver();
  ContactSolver(const ContactSolver&) = delete;
  ContactSolver& operator=(const ContactSolver&) = delete;

  // Solves the rows, starting from their impulses, and applies the change
  // of impulse to the velocities (which enter as the free velocities: those
  // after the step without contact forces).
  ContactSolverReport solve(std::vector<ContactRow>& rows, BodyVelocities& bodies,
                            const ContactSolverSettings& settings);

private:
  struct Factor;
  struct Workspace;
  std::unique_ptr<Factor> factor_;
  std::unique_ptr<Workspace> work_;
  std::unique_ptr<ParallelLoop> loop_;  // helpers sleep between solves
};

// A row's constants, fixed within a step: its 3x3 Delassus block
// W = J M^-1 J^T in the contact's frame (the change of the row's relative
// velocity per unit impulse) and the step sizes the sweeps take on it.
struct RowConstants {
  double normal_step = 0.0;      // rho_n = 1 / W_nn (N s per m/s)
  double tangent_step = 0.0;     // rho_t = 1 / the largest eigenvalue of W_tt (N s per m/s)
  Vec3 diagonal = Vec3::Zero();  // W_nn, W_t1t1, W_t2t2 (m/s per N s)
};
RowConstants row_constants(const ContactRow& row, const BodyVelocities& bodies);

// The relative velocity (m/s) of b's material point at the contact against
// a's, in the contact's frame (n, t1, t2).
Vec3 relative_velocity(const ContactRow& row, const BodyVelocities& bodies);

// How far (m/s) the relative velocity u (contact frame) of a row breaks the
// contact laws at the row's impulse: the normal velocity off its target
// where the contact presses, or below it where it does not; a sticking
// contact's slip; a sliding one's slip off the direction opposite its
// friction. Zero exactly when the row's laws hold.
double row_residual(const ContactRow& row, const Vec3& u);

// An orthonormal frame with n as its first row.
Mat3 contact_frame(const Vec3& n);

// The matrix of r's cross product: cross_matrix(r) v = r x v.
Mat3 cross_matrix(const Vec3& r);

}  // namespace ashlar
