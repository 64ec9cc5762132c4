// Rigid-block dynamics: what a structure does from rest under gravity, point
// loads and a prescribed ground motion.
//
// Method: non-smooth contact dynamics, Moreau-Jean time stepping (as in
// LMGC90 and Siconos). Each free block is a rigid body (exact mass, centroid
// and inertia of its polyhedron); supports are fixed. Per step of length h,
// with theta in [1/2, 1]:
//   v+ = v + h M^-1 f_theta + M^-1 P      (velocities after the step)
//   q+ = q + h ((1 - theta) v + theta v+) (positions; rotations likewise)
// where f_theta is the theta-weighted external force (gravity, point loads,
// the ground motion's inertia force) and P the contact impulses, found by
// projected Gauss-Seidel with global steps (contact_solver.hpp): unilateral contact with
// Newton's impact law (restitution e) and Coulomb friction, no dilatancy.
// A contact point takes part in a step when its gap, predicted half a step
// ahead, is within the contact tolerance. The solve starts from the last
// step's impulses, so a structure at rest that can stand stays at rest to
// the solver's tolerance: nothing is pre-stressed at the start (every
// impulse starts at zero) and overlaps are removed by moving positions
// only (a separate frictionless solve on pseudo-velocities that are then
// dropped), so the correction never adds kinetic energy.
//
// Ground motion: the supports move rigidly with a prescribed acceleration
// a_g(t) (m/s^2) of the pivot p (below), and may turn about p by a rotation
// R(t) = exp(theta(t)) (theta a rotation vector: axis times angle, rad;
// finite rotations). The simulation runs in the ground's frame, the supports'
// own: positions, velocities, displacements and a_g (as instruments fixed to
// the ground record it) are in the ground's axes. Every free block, of mass
// m and inertia I (ground axes, about its centroid c), with velocity v and
// angular velocity w relative to the ground, feels the body force and
// moment (about c) of the frame:
//   F = m R^T g - m a_g - m alpha x r - m omega x (omega x r) - 2 m omega x v
//   M = -I alpha - omega x (I omega) - omega x (I w) - w x (I omega) + I (w x omega)
// where r = c - p, g is gravity (the world's), omega and alpha the ground's
// angular velocity and acceleration in its axes, and F's terms after
// gravity the inertia force, Euler's, the centrifugal and Coriolis'. M is
// the rest of d/dt (I (omega + w)) = moments, written in the turning axes
// (Euler's torque -I alpha, the centrifugal -omega x I omega, and the
// three Coriolis terms); the block's own gyroscopic -w x (I w) comes with
// it. omega and alpha are central differences of R over the step h:
//   omega(t) = (d+ + d-) / 2, alpha(t) = (d+ - d-) / h,
//   d+ = log(R(t)^T R(t + h)) / h, d- = log(R(t - h)^T R(t)) / h,
// second-order in h and exact for a constant rate; theta(t) is called at
// times -h .. duration + h, so a ground already turning at time 0 turns the
// blocks with it (they start at rest relative to the ground). Each step
// weighs these forces at its two ends as it does a_g, with the blocks'
// positions and velocities at its start (as the gyroscopic moment): first
// order in h (a free block under a ground turning 0.6 rad in 1 s stays
// within 3e-5 m and rad of still in the world at h = 1 ms, half that at
// h / 2).
//
// Contacts (contact_points.hpp): found from the geometry at the start
// (ashlar's contact detection, plus corner contacts between convex blocks)
// up to a search distance, then kept with their blocks; a block and its
// neighbours are searched again once the block has moved (its farthest
// vertex) half the search distance since its last search, so no contact is
// missed. Neighbours come from a point grid of the centroids: sub-quadratic.
//
// Units: SI (m, kg, s, N). Throws InvalidArgument for options out of range,
// a structure with cables, explicit interfaces, overlapping blocks or no
// free block. An interrupt (Ctrl-C, a sandbox deadline: core/interrupt.hpp)
// ends the run with status `interrupted`, what was computed so far, and no
// verdict.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include "core/enum_names.hpp"
#include "core/types.hpp"
#include "dynamics/rigid_body.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct SimulationOptions {
  double duration = 1.0;      // simulated time (s), > 0
  double step = 1e-3;         // time step h (s), > 0 and <= duration
  double theta = 0.5;         // theta of the theta-method, in [0.5, 1]
  double friction = 0.7;      // Coulomb mu at every contact, >= 0 (inf: no sliding)
  double restitution = 0.0;   // Newton's e in [0, 1]: 0, masonry's plastic impacts
  Vec3 gravity{0.0, 0.0, -kGravity};  // m/s^2
  // Acceleration of the ground (the supports) at time t (m/s^2); empty: the
  // ground stays still. Called once per step, at its end time (and at 0).
  std::function<Vec3(double t)> ground_acceleration;
  // Rotation of the ground about ground_pivot at time t: the rotation
  // vector theta (rad, axis times angle) taking the ground's axes at rest to
  // where they are at t; empty: the ground does not turn. Called once per
  // step, at times -step .. duration + step (see the header).
  std::function<Vec3(double t)> ground_rotation;
  Vec3 ground_pivot = Vec3::Zero();  // m, the point the ground turns about (ground axes)
  // Steps between recorded frames (the first is at time 0, the last at the
  // end); 0: about 100 frames per simulated second (round(0.01 / step),
  // at least 1).
  int record_every = 0;
  // Contact detection: `angle` pairs faces as detection does, and gaps up to
  // the structure's contact tolerance (`tolerance`, relative_tolerance)
  // count as touching.
  ContactOptions contact;
  // Search distance for contacts (m); 0: 2 % of the smallest free block's
  // bounding-box diagonal. Larger means fewer searches, more points.
  double search_distance = 0.0;
  // A block has moved when a vertex of it has gone further than this
  // fraction of its bounding-box diagonal from where it started.
  double moved_fraction = 1e-3;
  // The run has settled when at the end no point of any free block moves
  // faster than this (m/s).
  double settle_speed = 1e-3;
  // Contact solver: sweeps per solve (see split_steps), and how far a
  // contact may break the contact laws, as a velocity (a fraction of 9.81
  // m/s^2 times the step, m/s), for a sweep to end the solve
  // (contact_solver.hpp). A block at rest then drifts by at most about
  // tolerance x 9.81 h per second. A structure at rest or shaken below
  // its load factor takes a few sweeps a step; a collapse's or a wall
  // shaken past its load factor hard steps a few hundred, the
  // interior-point method every 100 among them (contact_solver.hpp): six
  // collapsing arches (8,700 steps) converge at every step with 300, 1,000
  // or 3,000 sweeps at most (1 unconverged at 300), in 12.5, 13.2 and
  // 16.5 s (a step stopped at the most is taken again in halves).
  int max_sweeps = 1000;
  double tolerance = 1e-4;
  // Threads of the contact solve (contact_solver.hpp): 0, one per core (at
  // most 8); 1, one thread (the sweeps in the order of the load path, the
  // factorisation whole). Solves of fewer than 2,000 contact points run on
  // one thread whatever this is. A run gives the same numbers in every run
  // with the same threads; with other threads, numbers within the solver's
  // tolerance of them.
  int threads = 0;
  // Called after every step with the simulated time reached (s).
  std::function<void(double t)> progress;
};

enum class SimulationStatus { completed, interrupted };
inline constexpr EnumNames<SimulationStatus, 2> kSimulationStatusNames{
    {{{SimulationStatus::completed, "completed"}, {SimulationStatus::interrupted, "interrupted"}}}};

struct SimulationResult {
  SimulationStatus status = SimulationStatus::completed;
  // Verdict, only when completed: whether any block moved (moved_fraction),
  // and whether the motion had stopped at the end (settle_speed).
  bool moved = false;
  bool settled = false;

  int steps = 0;               // steps taken
  double time = 0.0;           // simulated time reached (s)
  double seconds = 0.0;        // wall-clock time of the run (s)
  // Largest displacement (m) of any vertex of block i from where it
  // started, over the whole run (0 for supports); and its largest over all
  // blocks, with the block (0-based, -1 when nothing moved).
  std::vector<double> displacement;
  double max_displacement = 0.0;
  int max_displacement_block = -1;

  // Info, not errors: sweeps summed over the steps, steps whose solve
  // stopped at max_sweeps, contact searches (each over the moved blocks and
  // their neighbours), and the most contact points taking part in a step.
  long long sweeps = 0;
  int unconverged_steps = 0;
  // Steps (and parts of steps) taken again as two half steps because their
  // contact solve stopped at max_sweeps within 1,000 times the tolerance:
  // split down to a 64th of the step where it must, at most 8 + a tenth of
  // the steps so far in a run, with the same velocity
  // tolerance (so the drift per second stays bounded as before). A step
  // counts as unconverged when a solve of it or of a part of it ended above
  // the tolerance. The sweeps and global steps above include the solves
  // split away. Steps are not split while the ground turns (ground_rotation).
  int split_steps = 0;
  int searches = 0;
  int max_active_contacts = 0;
  // The contact solve (contact_solver.hpp): its global steps and the
  // factorisations they made, summed over the steps; the largest residual
  // (m/s) any step's solve ended with (at most the tolerance, tolerance x
  // 9.81 m/s^2 x step, when every step converged), the end time (s) of
  // that step and the two blocks (0-based) of the contact point where it
  // was (-1, -1 when no step had a contact).
  long long global_steps = 0;
  long long factorizations = 0;
  double max_residual = 0.0;
  double max_residual_time = 0.0;
  std::pair<int, int> max_residual_blocks{-1, -1};

  // Recorded frames: times[k] (s) and poses[k][i] of every block i
  // (supports keep their place).
  std::vector<double> times;
  std::vector<std::vector<RigidPose>> poses;
};

SimulationResult simulate(const Structure& structure, const SimulationOptions& options);

// The poses of every block at time t (s), between the recorded frames
// around it: positions linear, rotations by slerp; clamped to the run.
std::vector<RigidPose> poses_at(const SimulationResult& result, double t);

// A copy of `structure` with each block placed at poses[i] (same names,
// supports and faces; point loads move with their blocks); cables and
// explicit interfaces, which simulate refuses, are not copied.
Structure posed_structure(const Structure& structure, const std::vector<RigidPose>& poses);

}  // namespace ashlar
