// Physics step benchmark: the shipped tianracer on the ground plane, stepped at 1 ms with its
// controllers' commands (rear wheel motors, hinge PID through efforts), for a few scenarios and
// solver settings, and with 50 free boxes (a world's dynamic models) in the car's path. Prints
// microseconds per step (wall and CPU), the real-time factor of physics alone, and heap
// allocations per step once warm (Bullet's and ours).
//
// Usage: physics_bench [tianracer_description dir] [steps per scenario]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <new>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <LinearMath/btAlignedAllocator.h>
#pragma GCC diagnostic pop

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/sim/robot_physics.h"

#ifndef TIANRACER_DESCRIPTION_DIR
#define TIANRACER_DESCRIPTION_DIR "../tianracer_description"
#endif

// Allocation counters: every operator new, and Bullet's aligned allocator.
static unsigned long g_allocations = 0;
void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
static void* countingAlignedAlloc(size_t size, int alignment) {
  ++g_allocations;
  void* p = nullptr;
  if (posix_memalign(&p, static_cast<size_t>(alignment < 16 ? 16 : alignment), size) != 0) return nullptr;
  return p;
}
static void countingAlignedFree(void* p) { std::free(p); }

using namespace tianracer_sim;

namespace {

struct Scenario {
  const char* name;
  double steer;   // hinge target, rad
  double speed;   // m/s at the rear wheels
  int iterations;
  int robots;
  int boxes = 0;  // free 0.2 m boxes (1 kg) on a 0.3 m grid ahead of the car, in its path
};

/// A free box as a world's dynamic model becomes: one body, one box collision.
RigidTree boxTree(double side, double mass) {
  RigidTree tree;
  TreeBody body;
  body.link = "link";
  body.merged_links = {"link"};
  body.X_BL["link"] = Eigen::Isometry3d::Identity();
  body.mass.mass = mass;
  body.mass.inertia = Eigen::Matrix3d::Identity() * mass * side * side / 6.0;
  CollisionGeometry g;
  g.shape.type = ShapeType::kBox;
  g.shape.size = Eigen::Vector3d::Constant(side);
  g.link = "link";
  body.collisions.push_back(g);
  tree.bodies.push_back(body);
  tree.links["link"] = {0, Eigen::Isometry3d::Identity()};
  return tree;
}

struct Result {
  double wall_us = 0.0, cpu_us = 0.0, allocs_per_step = 0.0;
};

Result run(const RobotModel& model, const Scenario& sc, int steps) {
  PhysicsOptions options;
  options.solver_iterations = sc.iterations;
  PhysicsWorld world(options);
  std::vector<PhysicsRobot*> cars;
  for (int i = 0; i < sc.robots; ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(0.0, 1.0 * i, 0.0095);
    cars.push_back(&world.robot(addRobotModel(&world, model, X, "car" + std::to_string(i))));
  }
  for (int i = 0; i < sc.boxes; ++i) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(0.6 + 0.3 * (i / 5), -0.6 + 0.3 * (i % 5), 0.1);
    world.addFreeBody(boxTree(0.2, 1.0), {SurfaceParams()}, X, "box" + std::to_string(i));
  }
  struct Pid {
    double prev = 0.0;
    bool first = true;
  };
  std::vector<Pid> pids(2 * cars.size());
  const int lr = cars[0]->jointIndex("left_rear_wheel_joint");
  const int rr = cars[0]->jointIndex("right_rear_wheel_joint");
  const int lh = cars[0]->jointIndex("left_steering_hinge_joint");
  const int rh = cars[0]->jointIndex("right_steering_hinge_joint");
  auto step = [&] {
    for (std::size_t c = 0; c < cars.size(); ++c) {
      PhysicsRobot& r = *cars[c];
      const int hinges[2] = {lh, rh};
      for (int h = 0; h < 2; ++h) {
        Pid& pid = pids[2 * c + h];
        const double e = sc.steer - r.jointPosition(hinges[h]);
        const double de = pid.first ? 0.0 : (e - pid.prev) / world.dt();
        pid.first = false;
        pid.prev = e;
        r.setJointEffort(hinges[h], 20.0 * e + 0.2 * de);
      }
      r.setJointVelocityTarget(lr, sc.speed / 0.032);
      r.setJointVelocityTarget(rr, sc.speed / 0.032);
    }
    world.step();
  };
  for (int k = 0; k < 1000; ++k) step();  // warm up: contacts, solver pools
  const unsigned long a0 = g_allocations;
  const auto w0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < steps; ++k) step();
  Result r;
  r.cpu_us = 1e6 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / steps;
  r.wall_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - w0).count() / steps;
  r.allocs_per_step = static_cast<double>(g_allocations - a0) / steps;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
  const std::string desc = argc > 1 ? argv[1] : TIANRACER_DESCRIPTION_DIR;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 20000;
  const std::string root = desc.substr(0, desc.find_last_of('/') == std::string::npos ? 0 : desc.find_last_of('/'));
  const char* old = std::getenv("ROS_PACKAGE_PATH");
  setenv("ROS_PACKAGE_PATH", ((root.empty() ? "." : root) + (old ? ":" + std::string(old) : "")).c_str(), 1);
  LoadOptions load;
  load.resolver.find_package = [&](const std::string& p) { return p == "tianracer_description" ? desc : std::string(); };
  RobotModel model;
  try {
    model = loadRobotModelFile(desc + "/urdf/tianracer_description.xacro", load);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "physics_bench: %s\n", e.what());
    return 1;
  }

  const int def = PhysicsOptions().solver_iterations;
  const Scenario scenarios[] = {
      {"parked", 0.0, 0.0, def, 1},
      {"straight 1 m/s", 0.0, 1.0, def, 1},
      {"full lock 2 m/s", 0.6, 2.0, def, 1},
      {"straight 1 m/s, 30 sweeps", 0.0, 1.0, 30, 1},
      {"straight 1 m/s, 50 sweeps", 0.0, 1.0, 50, 1},
      {"two cars, 1 m/s", 0.0, 1.0, def, 2},
      {"50 free boxes, car at 1 m/s", 0.0, 1.0, def, 1, 50},
  };
  std::printf("tianracer physics step (dt 1 ms, %d solver sweeps unless noted), %d steps per row\n",
              def, steps);
  std::printf("%-28s %10s %10s %12s %14s\n", "scenario", "wall us", "cpu us", "RTF (cpu)", "allocs/step");
  for (const Scenario& sc : scenarios) {
    const Result r = run(model, sc, steps);
    std::printf("%-28s %10.1f %10.1f %12.1f %14.3f\n", sc.name, r.wall_us, r.cpu_us,
                1000.0 / r.cpu_us, r.allocs_per_step);
  }
  return 0;
}
