// Sensor micro-benchmark: the cost of one output of each newer sensor, printed as one table.
//   - IMU (libgazebo_ros_imu_sensor) at 100 Hz on 1 ms physics steps: a sample is 10 recorded
//     steps plus one read, with the SDF noise off and with gaussian noise and bias on all axes;
//   - a 16 x 1800 3D lidar (velodyne conventions, +-15 deg, 360 deg) in racetrack.world;
//   - a stereo multicamera (libgazebo_ros_multicamera): both cameras of a frame, 2 x 320x240
//     (test model (a)'s) and 2 x 640x480, in racetrack.world.
// CPU times: the thread's for the IMU and the lidar (a shared machine's load disturbs them
// less than wall time); the process's for the cameras (llvmpipe rasterises on its own threads).
// Each figure is the best of 5 rounds.
//
//   sensor_bench [--world PATH]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/multicamera_config.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/plugins/imu/imu_sensor.h"
#include "tianracer_sim/world/world.h"

#include "bench_support.h"

namespace ts = tianracer_sim;

namespace {

using ts::bench::threadCpuSeconds;

double processCpu() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

double wallNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

Eigen::Isometry3d pose(double x, double y, double z, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(x, y, z);
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

struct Row {
  std::string what;
  std::string unit;
  double cpu = 0.0;
  double wall = 0.0;
};

// Best of 5 rounds of `n` calls of `f`, per call, in the unit's scale.
template <typename F>
Row best(const std::string& what, const std::string& unit, double scale, int n, double (*cpu)(),
         F&& f) {
  f();  // warm-up
  Row r{what, unit, 1e30, 1e30};
  for (int round = 0; round < 5; ++round) {
    const double c0 = cpu(), w0 = wallNow();
    for (int i = 0; i < n; ++i) f();
    r.cpu = std::min(r.cpu, scale * (cpu() - c0) / n);
    r.wall = std::min(r.wall, scale * (wallNow() - w0) / n);
  }
  return r;
}

// An IMU sample at 100 Hz on 1 ms steps: the car turning at 0.5 rad/s, 0.5 m/s.
Row imuRow(bool noise) {
  ts::ImuConfig c;
  c.name = "imu";
  c.link = "imu_link";
  c.update_rate = 100.0;
  c.has_plugin = true;
  c.topic_name = "imu";
  c.frame_name = "imu_link";
  c.seed = 1;
  if (noise) {
    for (auto* axes : {&c.rate_noise, &c.accel_noise}) {
      for (ts::ImuAxisNoise& a : *axes) {
        a.type = "gaussian";
        a.stddev = 0.01;
        a.bias_mean = 0.001;
        a.bias_stddev = 0.0001;
      }
    }
    c.gaussian_noise = 0.005;
  }
  ts::ImuSensor imu(c, Eigen::Vector3d(0, 0, -9.8));
  double t = 0.0;
  double checksum = 0.0;
  Row r = best(noise ? "IMU sample, SDF noise + bias on all axes" : "IMU sample, noise off",
               "us/sample", 1e6, 20000, &threadCpuSeconds, [&] {
                 for (int k = 0; k < 10; ++k) {
                   t += 0.001;
                   const Eigen::Isometry3d X = pose(std::sin(0.5 * t), 1.0 - std::cos(0.5 * t),
                                                    0.05, 0.5 * t);
                   imu.record(t, X);
                 }
                 checksum += imu.read().angular_velocity.z();
               });
  if (!std::isfinite(checksum)) std::cerr << "IMU produced a non-finite rate\n";
  r.what += " (10 steps recorded + 1 read)";
  return r;
}

Row lidar3dRow(const ts::Scene& scene) {
  ts::RaySensorConfig v;
  v.name = "velodyne";
  ts::bench::makeVelodyne16(v);
  v.update_rate = 10;
  ts::RayCaster caster;
  ts::RayScanBuffers buffers;
  std::vector<float> ranges;
  std::mt19937_64 rng(1);
  const std::vector<Eigen::Isometry3d> poses = {pose(0.09, 0, 0.15, 0), pose(3.9, 2.0, 0.15, M_PI / 2),
                                                pose(0.5, 4.0, 0.15, M_PI)};
  std::size_t i = 0;
  return best("3D lidar 16 x 1800, gaussianNoise 0.008 (racetrack)", "ms/scan", 1e3, 20,
              &threadCpuSeconds, [&] { scanRays(caster, scene, poses[i++ % poses.size()], v, rng,
                                         &buffers, &ranges); });
}

// A stereo pair as car_a writes it, at the given size.
ts::MultiCameraConfig stereo(int width, int height) {
  ts::SensorSpec s;
  s.name = "stereo_camera";
  s.type = "multicamera";
  s.link = "stereo_link";
  s.update_rate = 15;
  const std::string cam = "<horizontal_fov>1.3962634</horizontal_fov><image><width>" +
                          std::to_string(width) + "</width><height>" + std::to_string(height) +
                          "</height><format>R8G8B8</format></image><clip><near>0.02</near>"
                          "<far>300</far></clip><noise><type>gaussian</type><stddev>0.007"
                          "</stddev></noise>";
  s.xml = "<sensor type=\"multicamera\" name=\"stereo_camera\"><camera name=\"left\"><pose>0 0.06 0 "
          "0 0 0</pose>" + cam + "</camera><camera name=\"right\"><pose>0 -0.06 0 0 0 0</pose>" +
          cam + "</camera></sensor>";
  ts::PluginSpec p;
  p.filename = "libgazebo_ros_multicamera.so";
  p.params = {{"cameraName", "stereo"}, {"hackBaseline", "0.12"}};
  s.plugins.push_back(p);
  return ts::parseMultiCameraConfig(s, "bench");
}

Row stereoRow(ts::Renderer& renderer, const ts::Scene& scene, int width, int height) {
  const ts::MultiCameraConfig m = stereo(width, height);
  std::vector<std::unique_ptr<ts::CameraSensor>> cameras;
  for (const ts::CameraConfig& c : m.cameras) {
    cameras.push_back(std::make_unique<ts::CameraSensor>(c, renderer));
  }
  const Eigen::Isometry3d X_WL = pose(0.4, 0, 0.12, 0);
  return best("stereo multicamera 2 x " + std::to_string(width) + "x" + std::to_string(height) +
                  " colour + noise (racetrack)",
              "ms/pair", 1e3, 20, &processCpu, [&] {
                for (const auto& c : cameras) c->render(scene, X_WL);
              });
}

}  // namespace

int main(int argc, char** argv) {
  std::string world_path = std::string(TIANRACER_SIM_WORLDS_DIR) + "/racetrack.world";
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::string(argv[i]) == "--world") {
      world_path = argv[i + 1];
    } else {
      std::cerr << "usage: sensor_bench [--world PATH]\n";
      return 2;
    }
  }
  try {
    ts::Scene scene;
    ts::WorldLoadOptions wopt;
    wopt.warn = [](const std::string& w) { std::cerr << "warning: " << w << "\n"; };
    ts::addToScene(ts::loadWorldFile(world_path, wopt), scene);

    std::vector<Row> rows;
    rows.push_back(imuRow(false));
    rows.push_back(imuRow(true));
    rows.push_back(lidar3dRow(scene));
    ts::Renderer renderer(wopt.warn);
    rows.push_back(stereoRow(renderer, scene, 320, 240));
    rows.push_back(stereoRow(renderer, scene, 640, 480));

    std::printf("| sensor output | CPU | wall | unit |\n|---|---|---|---|\n");
    for (const Row& r : rows) {
      std::printf("| %s | %.3f | %.3f | %s |\n", r.what.c_str(), r.cpu, r.wall, r.unit.c_str());
    }
    std::printf("\nbest of 5 rounds each; CPU: the thread's (IMU, lidar) or the process's "
                "(cameras: llvmpipe's threads included)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sensor_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
