// Bullet's rigid-body dynamics on the walls of scripts/bench_simulate.lua,
// so that ashlar.simulate's cost and answer are measured beside a game
// engine's in the same run.
//
//   bench_bullet_walls BLOCKS_FILE DURATION FRICTION AMPLITUDE FREQUENCY [ITERATIONS]
//
// BLOCKS_FILE: one block a line, "support cx cy cz sx sy sz density"
// (support 1 or 0; centre and size of the axis-aligned box, m; density,
// kg/m^3), as bench_simulate.lua writes them. DURATION (s) simulated in
// steps of 1 ms; FRICTION mu of every contact; the ground shaken along x as
// a_g(t) = AMPLITUDE (m/s^2) sin(2 pi FREQUENCY t), applied as the body
// force -m a_g(t) on every free block (the supports stay still: the run is
// in the ground's frame, as ashlar's). ITERATIONS of the sequential-impulse
// solver per step (default Bullet's 10). Gravity 9.81 m/s^2 down z;
// restitution 0; no sleeping (ashlar solves every block every step).
//
// Prints one line: "bullet,BLOCKS,STEPS,CPU_S,CPU_S_PER_SIMULATED_S,MAX_DISPLACEMENT_M":
// the process's CPU time of the stepping (not of the set-up), and the
// largest displacement (m) of any free block's corner from where it
// started, over the run.
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Box {
  bool support = false;
  btVector3 centre, size;
  double density = 0.0;
};

std::vector<Box> read_boxes(const char* path) {
  std::ifstream in(path);
  std::vector<Box> boxes;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    int support = 0;
    double c[3], s[3], density = 0.0;
    if (fields >> support >> c[0] >> c[1] >> c[2] >> s[0] >> s[1] >> s[2] >> density) {
      boxes.push_back({support != 0, btVector3(c[0], c[1], c[2]), btVector3(s[0], s[1], s[2]), density});
    }
  }
  return boxes;
}

double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s BLOCKS_FILE DURATION FRICTION AMPLITUDE FREQUENCY [ITERATIONS]\n", argv[0]);
    return 2;
  }
  const std::vector<Box> boxes = read_boxes(argv[1]);
  const double duration = std::atof(argv[2]), friction = std::atof(argv[3]);
  const double amplitude = std::atof(argv[4]), frequency = std::atof(argv[5]);
  const int iterations = argc > 6 ? std::atoi(argv[6]) : 10;
  if (boxes.empty() || !(duration > 0.0) || !(friction >= 0.0) || iterations < 1) {
    std::fprintf(stderr, "bench_bullet_walls: no blocks in %s, or a bad duration, friction or iteration count\n",
                 argv[1]);
    return 2;
  }
  const double step = 1e-3;

  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, 0, -9.81));
  world.getSolverInfo().m_numIterations = iterations;

  std::vector<std::unique_ptr<btBoxShape>> shapes;
  std::vector<std::unique_ptr<btDefaultMotionState>> states;
  std::vector<std::unique_ptr<btRigidBody>> bodies;
  std::vector<btRigidBody*> free_bodies;
  std::vector<btVector3> half_sizes, starts;
  for (const Box& box : boxes) {
    shapes.push_back(std::make_unique<btBoxShape>(box.size / 2));
    const double mass = box.support ? 0.0 : box.density * box.size.x() * box.size.y() * box.size.z();
    btVector3 inertia(0, 0, 0);
    if (mass > 0.0) shapes.back()->calculateLocalInertia(mass, inertia);
    btTransform pose;
    pose.setIdentity();
    pose.setOrigin(box.centre);
    states.push_back(std::make_unique<btDefaultMotionState>(pose));
    btRigidBody::btRigidBodyConstructionInfo info(mass, states.back().get(), shapes.back().get(), inertia);
    // Bullet multiplies the two bodies' frictions: each gets sqrt(mu).
    info.m_friction = std::sqrt(friction);
    info.m_restitution = 0.0;
    bodies.push_back(std::make_unique<btRigidBody>(info));
    bodies.back()->setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(bodies.back().get());
    if (mass > 0.0) {
      free_bodies.push_back(bodies.back().get());
      half_sizes.push_back(box.size / 2);
      starts.push_back(box.centre);
    }
  }

  const int steps = static_cast<int>(std::ceil(duration / step - 1e-9));
  double largest = 0.0;
  const double started = cpu_seconds();
  for (int k = 0; k < steps; ++k) {
    // The force over step k: a_g at its middle.
    const double ground = amplitude * std::sin(2.0 * M_PI * frequency * (k + 0.5) * step);
    if (ground != 0.0) {
      for (btRigidBody* body : free_bodies) body->applyCentralForce(btVector3(-ground / body->getInvMass(), 0, 0));
    }
    world.stepSimulation(step, 0);
    for (size_t i = 0; i < free_bodies.size(); ++i) {
      const btTransform& pose = free_bodies[i]->getWorldTransform();
      for (int corner = 0; corner < 8; ++corner) {
        const btVector3 local((corner & 1 ? 1 : -1) * half_sizes[i].x(), (corner & 2 ? 1 : -1) * half_sizes[i].y(),
                              (corner & 4 ? 1 : -1) * half_sizes[i].z());
        largest = std::max(largest, static_cast<double>((pose * local - (starts[i] + local)).length()));
      }
    }
  }
  const double seconds = cpu_seconds() - started;
  std::printf("bullet,%zu,%d,%.3f,%.3f,%.4g\n", boxes.size(), steps, seconds, seconds / (steps * step), largest);
  for (auto& body : bodies) world.removeRigidBody(body.get());
  return 0;
}
