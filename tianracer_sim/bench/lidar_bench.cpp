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
#include <ctime>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/world/world.h"

#include "bench_support.h"

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

/// One strategy on one scene, timed in rounds interleaved with the other strategies so that
/// all see the same machine load (it is shared: 2 cores); the best round is reported.
struct Trial {
  std::string name;
  bool with_car = false;
  Scene scene;
  std::unique_ptr<RayCaster> caster;
  double build_ms = 0.0;
  double best_s_per_scan = 1e9;
  long finite = 0, total = 0;
  RayScanBuffers buffers;  // beam directions, reused across rounds
};

const std::vector<Eigen::Isometry3d>& trackPoses() {
  static const std::vector<Eigen::Isometry3d> poses = {
      pose(0.093603, 0, 0.14567, 0),            // spawn
      pose(3.9, 2.0, 0.14567, M_PI / 2),        // right side
      pose(0.5, 4.0, 0.14567, M_PI),            // top straight
      pose(-3.6, 0.6, 0.14567, -3 * M_PI / 4),  // bottom-left corner
      pose(3.3, 0.3, 0.14567, M_PI / 4)};       // bottom-right corner
  return poses;
}

void runRound(Trial& t, int scans, const std::vector<int>& car, std::mt19937_64& rng,
              std::vector<float>& ranges) {
  const RaySensorConfig c = seedLidar();
  const auto& poses = trackPoses();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < scans; ++i) {
    if (t.with_car)
      for (int b : car) t.scene.bodies[b].X_WB.translation().x() += 1e-6;
    scanRays(*t.caster, t.scene, poses[i % poses.size()], c, rng, &t.buffers, &ranges);
    for (float r : ranges) t.finite += std::isfinite(r);
    t.total += ranges.size();
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  t.best_s_per_scan = std::min(t.best_s_per_scan, s / scans);
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

  std::vector<Trial> trials;
  for (PrimitiveMode p :
       {PrimitiveMode::kHybrid, PrimitiveMode::kAnalytic, PrimitiveMode::kTessellated}) {
    for (RayQueryMode q : {RayQueryMode::kSingle, RayQueryMode::kPacket16, RayQueryMode::kStream}) {
      for (int with_car = 0; with_car < 2; ++with_car) {
        Trial t;
        t.name = std::string(p == PrimitiveMode::kHybrid     ? "hybrid"
                             : p == PrimitiveMode::kAnalytic ? "user-geometry"
                                                             : "tessellated") +
                 " + " +
                 (q == RayQueryMode::kSingle     ? "rtcIntersect1 loop"
                  : q == RayQueryMode::kPacket16 ? "rtcIntersect16"
                                                 : "rtcIntersect1M");
        t.with_car = with_car;
        t.scene = with_car ? car_scene : world_scene;
        RayCasterOptions o;
        o.primitives = p;
        o.query = q;
        t.caster = std::make_unique<RayCaster>(o);
        const auto t0 = std::chrono::steady_clock::now();
        t.caster->build(t.scene);
        t.build_ms =
            1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        trials.push_back(std::move(t));
      }
    }
  }
  const int rounds = 10;
  std::mt19937_64 rng(1);
  std::vector<float> ranges;
  for (Trial& t : trials) runRound(t, 20, car, rng, ranges);  // warm up
  for (int r = 0; r < rounds; ++r)
    for (Trial& t : trials) runRound(t, std::max(1, scans / rounds), car, rng, ranges);

  std::printf("racetrack.world: %zu bodies, %zu items (+%zu car bodies, meshes); seed lidar 1081 "
              "beams with noise; %d scans per row over 5 poses along the track; best of %d "
              "interleaved rounds\n\n",
              world_scene.bodies.size(), world_scene.items.size(), car.size(), scans, rounds);
  std::printf("%-36s %-10s %9s %9s %9s %7s\n", "strategy", "scene", "ms/scan", "Mrays/s",
              "build ms", "hits");
  for (const Trial& t : trials)
    std::printf("%-36s %-10s %9.4f %9.2f %9.2f %6.1f%%\n", t.name.c_str(),
                t.with_car ? "world+car" : "world", 1e3 * t.best_s_per_scan,
                1081 / t.best_s_per_scan / 1e6, t.build_ms, 100.0 * t.finite / t.total);

  // A 3D lidar: 16 rings x 1800 beams (+-15 deg, 360 deg), velodyne range model and noise, on
  // the default caster, from the car's lidar mount; sensor-side cost only (no message).
  {
    RaySensorConfig v = seedLidar();
    bench::makeVelodyne16(v);
    RayCaster caster;
    RayScanBuffers buffers;
    const auto& poses = trackPoses();
    const int n3d = std::max(20, scans / 20);
    double best = 1e9, best_quiet = 1e9;
    long points = 0, total = 0;
    const auto cpuNow = bench::threadCpuSeconds;
    for (int round = 0; round < 10; ++round) {
      v.cloud_noise = round % 2 ? 0.0 : 0.008;  // noise on and off, interleaved
      const double t0 = cpuNow();
      for (int i = 0; i < n3d; ++i) {
        for (int b : car) car_scene.bodies[b].X_WB.translation().x() += 1e-6;
        scanRays(caster, car_scene, poses[i % poses.size()], v, rng, &buffers, &ranges);
        if (round == 0) {
          for (float r : ranges) points += std::isfinite(r);
          total += ranges.size();
        }
      }
      const double s_per_scan = (cpuNow() - t0) / n3d;
      double& b = round % 2 ? best_quiet : best;
      b = std::min(b, s_per_scan);
    }
    std::printf("\n3D lidar 16 x 1800 (velodyne, hybrid + rtcIntersect16, world+car): %.3f CPU ms/scan "
                "(%.2f Mrays/s) with gaussianNoise 0.008, %.3f ms without; %.1f%% of rays give a "
                "point; best of 5 rounds of %d scans each\n",
                1e3 * best, 16 * 1800 / best / 1e6, 1e3 * best_quiet,
                100.0 * points / std::max(1L, total), n3d);
  }
  return 0;
}
