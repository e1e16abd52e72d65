// Physics step benchmark: the shipped tianracer on the ground plane, stepped at 1 ms with its
// controllers' commands (rear wheel motors, hinge PID through efforts), for a few scenarios and
// solver settings, with 50 free boxes (a world's dynamic models) in the car's path, and 50
// resting boxes asleep or kept awake. Prints microseconds per step (wall and CPU), the real-time
// factor of physics alone, and heap allocations per step once warm (Bullet's and ours).
//
// A second table: the car circling on issue 24's movable track (two 1,665 kg links with mesh
// collisions, test/data/worlds/movable_track) with the track's meshes as a static triangle mesh
// (btBvhTriangleMeshShape), as GImpact meshes on a free body (what world models get), as a
// convex decomposition (HACD, Debian's libbullet-extras; hulls of the parts) and as one convex
// hull per mesh (what world models got before): cost per step, build time and how the car
// rides (tilt, speed).
//
// Each row ends with a fingerprint of the final state (FNV-1a over the bits of every car's and
// box's base pose and twist and joint positions and velocities): equal fingerprints across
// builds mean a setting changed nothing in the trajectory, to the last bit.
//
// Usage: physics_bench [tianracer_description dir] [steps per scenario] [scenario filter]
//   filter: only the scenario of that name, else those whose name contains it ("car": the
//   car scenarios without boxes), and no track table.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <new>
#include <string>
#include <vector>

#include <fstream>
#include <functional>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <HACD/hacdHACD.h>
#include <LinearMath/btAlignedAllocator.h>
#pragma GCC diagnostic pop

#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/sim/robot_physics.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

#ifndef TIANRACER_DESCRIPTION_DIR
#define TIANRACER_DESCRIPTION_DIR "../tianracer_description"
#endif
#ifndef TIANRACER_SIM_DIR
#define TIANRACER_SIM_DIR "."
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
  /// 1 / 0: the boxes stand behind the car, out of its way, and may sleep / are kept awake
  /// (warm-up long enough for them to fall asleep); -1: in its path, never sleeping.
  int resting_boxes_sleep = -1;
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
  std::uint64_t state = 0;  // fingerprint of the final state
};

/// FNV-1a over the bits of the doubles fed to it.
struct Fingerprint {
  std::uint64_t h = 1469598103934665603ull;
  void add(double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 8; ++i) {
      h ^= (bits >> (8 * i)) & 0xffu;
      h *= 1099511628211ull;
    }
  }
  void add(const PhysicsRobot& r) {
    const Eigen::Isometry3d X = r.basePose();
    for (int i = 0; i < 12; ++i) add(X.matrix().data()[i]);
    const Twist t = r.baseTwist();
    for (int i = 0; i < 3; ++i) add(t.linear[i]), add(t.angular[i]);
    for (std::size_t j = 0; j < r.joints().size(); ++j) {
      add(r.jointPosition(static_cast<int>(j)));
      add(r.jointVelocity(static_cast<int>(j)));
    }
  }
};

/// The car's controllers as in run(): hinges to `steer` by a PD on their efforts, rear wheels
/// at speed / r.
struct CarDriver {
  PhysicsRobot* car;
  int lr, rr, hinges[2];
  double prev[2] = {0.0, 0.0};
  bool first = true;
  explicit CarDriver(PhysicsRobot* c) : car(c) {
    lr = c->jointIndex("left_rear_wheel_joint");
    rr = c->jointIndex("right_rear_wheel_joint");
    hinges[0] = c->jointIndex("left_steering_hinge_joint");
    hinges[1] = c->jointIndex("right_steering_hinge_joint");
  }
  void command(double steer, double speed, double dt) {
    for (int h = 0; h < 2; ++h) {
      const double e = steer - car->jointPosition(hinges[h]);
      const double de = first ? 0.0 : (e - prev[h]) / dt;
      prev[h] = e;
      car->setJointEffort(hinges[h], 20.0 * e + 0.2 * de);
    }
    first = false;
    car->setJointVelocityTarget(lr, speed / 0.032);
    car->setJointVelocityTarget(rr, speed / 0.032);
  }
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
    if (sc.resting_boxes_sleep >= 0) X.translation().x() = -1.0 - 0.3 * (i / 5);  // behind it
    const int b = world.addFreeBody(boxTree(0.2, 1.0), {SurfaceParams()}, X, "box" + std::to_string(i));
    world.freeBody(b).allowSleep(sc.resting_boxes_sleep == 1);
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
  // Warm up: contacts, solver pools (and resting boxes asleep: 1 s after they stop).
  const int warmup = sc.resting_boxes_sleep >= 0 ? 3000 : 1000;
  for (int k = 0; k < warmup; ++k) step();
  if (sc.resting_boxes_sleep == 1) {
    for (int i = 0; i < world.freeBodyCount(); ++i) {
      if (!world.freeBody(i).asleep()) std::fprintf(stderr, "physics_bench: box %d is awake\n", i);
    }
  }
  const unsigned long a0 = g_allocations;
  const auto w0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < steps; ++k) step();
  Result r;
  r.cpu_us = 1e6 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / steps;
  r.wall_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - w0).count() / steps;
  r.allocs_per_step = static_cast<double>(g_allocations - a0) / steps;
  Fingerprint f;
  for (const PhysicsRobot* c : cars) f.add(*c);
  for (int i = 0; i < world.freeBodyCount(); ++i) f.add(world.freeBody(i));
  r.state = f.h;
  return r;
}

// --- The car on the movable track ------------------------------------------------------------

enum class TrackKind { kStatic, kGImpact, kDecomposition, kHull };

/// Writes the convex parts HACD finds in `path` as ASCII STL files (part_<k>.stl in dir);
/// returns their paths.
std::vector<std::string> decompose(const std::string& path, const std::string& dir, int* hulls) {
  const TriangleMesh mesh = loadMeshFile(path);
  std::vector<HACD::Vec3<HACD::Real>> points;
  std::vector<HACD::Vec3<long>> triangles;
  for (const auto& v : mesh.vertices) points.emplace_back(v.x(), v.y(), v.z());
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    triangles.emplace_back(mesh.indices[3 * t], mesh.indices[3 * t + 1], mesh.indices[3 * t + 2]);
  }
  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  hacd.SetCompacityWeight(0.1);
  hacd.SetVolumeWeight(0.0);
  hacd.SetNClusters(1);         // as few as the concavity allows
  hacd.SetNVerticesPerCH(100);
  hacd.SetConcavity(0.01);      // m: parts deviate at most ~1 cm from the mesh
  hacd.SetAddExtraDistPoints(true);
  hacd.SetAddNeighboursDistPoints(true);
  hacd.SetAddFacesPoints(true);
  hacd.Compute();
  std::vector<std::string> out;
  *hulls = static_cast<int>(hacd.GetNClusters());
  for (std::size_t c = 0; c < hacd.GetNClusters(); ++c) {
    std::vector<HACD::Vec3<HACD::Real>> p(hacd.GetNPointsCH(c));
    std::vector<HACD::Vec3<long>> t(hacd.GetNTrianglesCH(c));
    hacd.GetCH(c, p.data(), t.data());
    const std::string file = dir + "/" + std::to_string(out.size()) + "_" +
                             path.substr(path.find_last_of('/') + 1);
    std::ofstream f(file);
    f << "solid part\n";
    for (const auto& tri : t) {
      f << " facet normal 0 0 0\n  outer loop\n";
      for (const long i : {tri.X(), tri.Y(), tri.Z()}) {
        const auto& q = p[i];
        f << "   vertex " << q.X() << " " << q.Y() << " " << q.Z() << "\n";
      }
      f << "  endloop\n endfacet\n";
    }
    f << "endsolid part\n";
    out.push_back(file);
  }
  return out;
}

struct TrackResult {
  double wall_us = 0.0, cpu_us = 0.0, build_ms = 0.0;
  double max_tilt = 0.0, mean_speed = 0.0, max_z = 0.0;
  int shapes = 0;
};

/// The track's two links as a body each of a 1,665 kg rigid tree whose collisions are `meshes`
/// (per link): a robot's tree, whose meshes are hulls (the decomposition's parts, or the whole
/// mesh as before).
RigidTree trackTree(const WorldDescription& desc, const std::vector<std::vector<std::string>>& meshes) {
  const ModelDescription& m = desc.models.at(0);
  RigidTree tree;
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const LinkDescription& link = m.links[l];
    TreeBody body;
    body.link = link.name;
    body.merged_links = {link.name};
    body.X_BL[link.name] = link.X_ML;
    MassProperties m_L;
    m_L.mass = link.inertial.mass;
    m_L.com = link.inertial.X_LI.translation();
    m_L.inertia = link.inertial.inertia;
    body.mass = transformMassProperties(m_L, link.X_ML);
    for (const std::string& file : meshes[l]) {
      CollisionGeometry g;
      g.link = link.name;
      g.X_BG = link.X_ML;
      g.shape.type = ShapeType::kMesh;
      g.shape.mesh_path = file;
      body.collisions.push_back(g);
    }
    tree.links[link.name] = {static_cast<int>(l), link.X_ML};
    tree.bodies.push_back(body);
  }
  return tree;
}

TrackResult runTrack(const RobotModel& model, TrackKind kind, int steps) {
  const std::string dir = std::string(TIANRACER_SIM_DIR) + "/test/data/worlds/movable_track";
  WorldDescription desc = loadWorldFile(dir + "/movable_track.world");
  desc.models.at(0).is_static = kind == TrackKind::kStatic;
  PhysicsWorld world(physicsOptionsFor(desc));
  TrackResult r;
  const auto b0 = std::chrono::steady_clock::now();
  if (kind == TrackKind::kStatic || kind == TrackKind::kGImpact) {
    r.shapes = addWorldToPhysics(desc, &world, {});
  } else {
    std::vector<std::vector<std::string>> meshes;
    char tmpl[] = "/tmp/physics_bench_XXXXXX";
    const std::string tmp = mkdtemp(tmpl) ? tmpl : "/tmp";
    for (const LinkDescription& l : desc.models[0].links) {
      const std::string file = l.collisions.at(0).shape.mesh_path;
      int hulls = 1;
      meshes.push_back(kind == TrackKind::kHull ? std::vector<std::string>{file}
                                                : decompose(file, tmp, &hulls));
      r.shapes += hulls;
    }
    world.addRobot(trackTree(desc, meshes), {}, desc.models[0].X_WM, "track");
  }
  r.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - b0).count();
  // Circling at 1 m/s, steering 0.2 rad (radius ~1.23 m) around the track's middle.
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(0.0, -1.23, 0.02 + 0.0095);
  CarDriver car(&world.robot(addRobotModel(&world, model, X, "tianracer")));
  const double steer = 0.2, speed = 1.0;
  for (int k = 0; k < 1000; ++k) {
    car.command(steer, k < 300 ? 0.0 : speed, world.dt());
    world.step();
  }
  double speed_sum = 0.0;
  const auto w0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  for (int k = 0; k < steps; ++k) {
    car.command(steer, speed, world.dt());
    world.step();
    const Eigen::Isometry3d X_WB = car.car->basePose();
    r.max_tilt = std::max(r.max_tilt, std::acos(std::min(1.0, X_WB.linear()(2, 2))));
    r.max_z = std::max(r.max_z, X_WB.translation().z());
    speed_sum += car.car->baseTwist().linear.head<2>().norm();
  }
  r.cpu_us = 1e6 * static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC / steps;
  r.wall_us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - w0).count() / steps;
  r.mean_speed = speed_sum / steps;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree);
  const std::string desc = argc > 1 ? argv[1] : TIANRACER_DESCRIPTION_DIR;
  const int steps = argc > 2 ? std::atoi(argv[2]) : 20000;
  const std::string filter = argc > 3 ? argv[3] : "";
  if (steps < 1) {
    std::fprintf(stderr, "physics_bench: steps per scenario must be >= 1, got '%s'\n", argv[2]);
    return 1;
  }
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
      {"parked, 50 resting awake", 0.0, 0.0, def, 1, 50, 0},
      {"parked, 50 resting asleep", 0.0, 0.0, def, 1, 50, 1},
  };
  std::printf("tianracer physics step (dt 1 ms, %d solver sweeps unless noted), %d steps per row\n",
              def, steps);
  std::printf("%-28s %10s %10s %12s %14s %16s\n", "scenario", "wall us", "cpu us", "RTF (cpu)",
              "allocs/step", "state");
  bool exact = false;  // a filter that names one scenario selects only that one
  for (const Scenario& sc : scenarios) exact = exact || filter == sc.name;
  int ran = 0;
  for (const Scenario& sc : scenarios) {
    const bool selected = filter.empty() || (exact ? filter == sc.name
                                             : filter == "car" ? sc.boxes == 0
                                                               : std::string(sc.name).find(filter) != std::string::npos);
    if (!selected) continue;
    ++ran;
    const Result r = run(model, sc, steps);
    std::printf("%-28s %10.1f %10.1f %12.1f %14.3f %16.16llx\n", sc.name, r.wall_us, r.cpu_us,
                1000.0 / r.cpu_us, r.allocs_per_step, static_cast<unsigned long long>(r.state));
  }
  if (ran == 0) {
    std::fprintf(stderr, "physics_bench: no scenario matches the filter '%s'\n", filter.c_str());
    return 1;
  }
  if (!filter.empty()) return 0;

  const int track_steps = std::min(steps, 10000);
  std::printf("\ntianracer circling at 1 m/s (steering 0.2 rad) on issue 24's movable track (two "
              "1,665 kg mesh links), %d steps per row\n", track_steps);
  std::printf("%-34s %8s %8s %9s %7s %10s %10s %10s\n", "track collisions", "wall us", "cpu us",
              "build ms", "shapes", "max tilt", "max z m", "speed m/s");
  const std::pair<TrackKind, const char*> kinds[] = {
      {TrackKind::kStatic, "static triangle mesh (BVH)"},
      {TrackKind::kGImpact, "free body, GImpact (world models)"},
      {TrackKind::kDecomposition, "free body, HACD convex parts"},
      {TrackKind::kHull, "free body, one hull per mesh (old)"}};
  for (const auto& [kind, name] : kinds) {
    const TrackResult r = runTrack(model, kind, track_steps);
    std::printf("%-34s %8.1f %8.1f %9.1f %7d %10.4f %10.4f %10.4f\n", name, r.wall_us, r.cpu_us,
                r.build_ms, r.shapes, r.max_tilt, r.max_z, r.mean_speed);
  }
  return 0;
}
