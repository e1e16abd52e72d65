// Lidar benchmark: the seed's hokuyo (1081 beams) in racetrack.world, for each ray-casting
// strategy: rays/s and ms per scan. Usage: lidar_bench [tianracer_sim source dir] [scans]
//
// Two scenes: the world alone, and the world plus a car (chassis and four wheels from
// tianracer_description's meshes as moving bodies, nudged before every scan so that each scan
// pays for the instance update and the top-level commit, as in the sim).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/lidar/ray_sensor.h"
#include "tianracer_sim/world/world.h"

#ifndef TIANRACER_SIM_DIR
#define TIANRACER_SIM_DIR "."
#endif

using namespace tianracer_sim;

namespace {

Eigen::Isometry3d pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

RaySensorConfig seedLidar() {
  RaySensorConfig c;
  c.name = "hokuyo_sensor";
  c.samples = 1081;
  c.min_angle = -2.3561944902;
  c.max_angle = 2.3561944902;
  c.range_min = 0.1;
  c.range_max = 10.0;
  c.noise.type = "gaussian";
  c.noise.stddev = 0.01;
  c.update_rate = 40;
  return c;
}

// Car bodies (base_link pose X_WC): chassis + 4 wheels, offsets from the seed's joints.
std::vector<int> addCar(Scene& scene, const std::string& meshes) {
  struct Part {
    const char* link;
    const char* mesh;
    Eigen::Vector3d xyz;
  };
  const Part parts[] = {{"chassis", "base_link.STL", {0, 0, 0}},
                        {"left_front_wheel", "left_front_wheel.STL", {0.125, 0.085, 0.0225}},
                        {"right_front_wheel", "right_front_wheel.STL", {0.125, -0.085, 0.0225}},
                        {"left_rear_wheel", "left_rear_wheel.STL", {-0.125, 0.085, 0.0225}},
                        {"right_rear_wheel", "right_rear_wheel.STL", {-0.125, -0.085, 0.0225}},
                        {"lidar", "lidar.STL", {0.093603, 0, 0.12377}}};
  std::vector<int> bodies;
  for (const Part& p : parts) {
    SceneBody b;
    b.name = std::string("tianracer::") + p.link;
    b.model = "tianracer";
    b.is_static = false;
    b.X_WB = pose(p.xyz.x(), p.xyz.y(), p.xyz.z() + 0.0095, 0);
    const int i = scene.addBody(b);
    SceneItem it;
    it.body = i;
    it.shape.type = ShapeType::kMesh;
    it.shape.mesh_path = meshes + "/" + p.mesh;
    it.collision = true;
    scene.items.push_back(it);
    bodies.push_back(i);
  }
  return bodies;
}

struct Result {
  double ms_per_scan;
  double rays_per_s;
  double build_ms;
  double finite_fraction;
};

Result run(const Scene& scene_in, const RayCasterOptions& options, int scans, bool move_car,
           const std::vector<int>& car) {
  Scene scene = scene_in;
  const RaySensorConfig c = seedLidar();
  const std::vector<Eigen::Isometry3d> poses = {
      pose(0.093603, 0, 0.14567, 0),            // spawn
      pose(3.9, 2.0, 0.14567, M_PI / 2),        // right side
      pose(0.5, 4.0, 0.14567, M_PI),            // top straight
      pose(-3.6, 0.6, 0.14567, -3 * M_PI / 4),  // bottom-left corner
      pose(3.3, 0.3, 0.14567, M_PI / 4)};       // bottom-right corner
  RayCaster caster(options);
  const auto t0 = std::chrono::steady_clock::now();
  caster.build(scene);
  const auto t1 = std::chrono::steady_clock::now();
  std::mt19937_64 rng(1);
  std::vector<float> ranges;
  long finite = 0, total = 0;
  for (int i = 0; i < 50; ++i) caster.scan(scene, poses[i % poses.size()], c, rng, &ranges);
  // Best of 5 rounds: the machine is shared (2 cores), the minimum is the cost of the code.
  double best = 1e9;
  for (int round = 0; round < 5; ++round) {
    const auto t2 = std::chrono::steady_clock::now();
    for (int i = 0; i < scans / 5; ++i) {
      if (move_car)
        for (int b : car) scene.bodies[b].X_WB.translation().x() += 1e-6;
      caster.scan(scene, poses[i % poses.size()], c, rng, &ranges);
      for (float r : ranges) finite += std::isfinite(r);
      total += ranges.size();
    }
    const auto t3 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t3 - t2).count() / (scans / 5));
  }
  return {1e3 * best, c.samples / best, 1e3 * std::chrono::duration<double>(t1 - t0).count(),
          double(finite) / total};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : TIANRACER_SIM_DIR;
  const int scans = argc > 2 ? std::atoi(argv[2]) : 4000;
  const std::string world_path = dir + "/worlds/racetrack.world";
  const std::string meshes = dir + "/../tianracer_description/meshes";

  Scene world_scene;
  try {
    addToScene(loadWorldFile(world_path), world_scene);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lidar_bench: %s\n", e.what());
    return 1;
  }
  Scene car_scene = world_scene;
  const std::vector<int> car = addCar(car_scene, meshes);

  struct Strategy {
    const char* name;
    RayCasterOptions options;
  };
  std::vector<Strategy> strategies;
  for (PrimitiveMode p :
       {PrimitiveMode::kHybrid, PrimitiveMode::kAnalytic, PrimitiveMode::kTessellated}) {
    for (RayQueryMode q : {RayQueryMode::kSingle, RayQueryMode::kPacket16, RayQueryMode::kStream}) {
      RayCasterOptions o;
      o.primitives = p;
      o.query = q;
      static std::vector<std::string> names;
      names.push_back(std::string(p == PrimitiveMode::kHybrid     ? "hybrid"
                                  : p == PrimitiveMode::kAnalytic ? "user-geometry"
                                                                  : "tessellated") +
                      " + " +
                      (q == RayQueryMode::kSingle ? "rtcIntersect1 loop"
                       : q == RayQueryMode::kPacket16 ? "rtcIntersect16" : "rtcIntersect1M"));
      strategies.push_back({nullptr, o});
      strategies.back().name = names.back().c_str();
    }
  }

  std::printf("racetrack.world: %zu bodies, %zu items; seed lidar 1081 beams, %d scans per row, "
              "5 poses along the track; best of 5 rounds\n\n",
              world_scene.bodies.size(), world_scene.items.size(), scans);
  std::printf("%-40s %-10s %10s %12s %10s %8s\n", "strategy", "scene", "ms/scan", "Mrays/s",
              "build ms", "hits");
  for (const Strategy& s : strategies) {
    for (int with_car = 0; with_car < 2; ++with_car) {
      const Result r = run(with_car ? car_scene : world_scene, s.options, scans, with_car, car);
      std::printf("%-40s %-10s %10.4f %12.2f %10.2f %7.1f%%\n", s.name,
                  with_car ? "world+car" : "world", r.ms_per_scan, r.rays_per_s / 1e6, r.build_ms,
                  100 * r.finite_fraction);
    }
  }
  return 0;
}
