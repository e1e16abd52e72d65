// Render benchmark: ms per frame of the seed's 800x800 camera (colour + noise) and of its
// 640x480 depth camera (colour + depth + organized cloud), the tianracer on the racetrack
// world; then the same cameras on the textured lane track, with its floor texture and with
// the texture taken off (same geometry). Also writes PNGs for people: a chase view, the
// camera's and the depth camera's frames, and the camera's view of the lane track.
//
//   render_bench [--frames N] [--world PATH] [--png-dir DIR]
//   LP_NUM_THREADS=1 render_bench   # Mesa llvmpipe's rasteriser threads (default: the cores)
//   render_bench --cost-table [--frames N]   # what a frame costs, part by part (see costTable)
//   render_bench --threads-probe [--frames N]  # one line of the cost table's thread rows (its child)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <unistd.h>

#include <urdf_model/model.h>

#include "tianracer_sim/mesh/mesh_loader.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/image_noise.h"
#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/render/png_writer.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/world/world.h"

namespace ts = tianracer_sim;

namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  X.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  return X;
}

// The robot at zero joint positions: one body per link, its visuals as items. Returns the
// link poses (model frame) by name.
std::map<std::string, Eigen::Isometry3d> addRobot(const ts::RobotModel& model, const Eigen::Isometry3d& X_WM,
                                                  ts::Scene* scene, std::map<std::string, int>* bodies) {
  std::map<std::string, Eigen::Isometry3d> X_ML;
  std::function<void(const urdf::LinkConstSharedPtr&, const Eigen::Isometry3d&)> visit =
      [&](const urdf::LinkConstSharedPtr& link, const Eigen::Isometry3d& X) {
        X_ML[link->name] = X;
        const int body = scene->addBody(ts::SceneBody{"tianracer::" + link->name, "tianracer", false, X_WM * X});
        (*bodies)[link->name] = body;
        std::string gz;
        const auto ext = model.ext.links.find(link->name);
        if (ext != model.ext.links.end()) gz = ext->second.material;
        for (const auto& visual : link->visual_array) {
          if (!visual || !visual->geometry) continue;
          ts::SceneItem item;
          item.body = body;
          item.X_BS = toIsometry(visual->origin);
          switch (visual->geometry->type) {
            case urdf::Geometry::MESH: {
              const auto* m = static_cast<const urdf::Mesh*>(visual->geometry.get());
              item.shape.type = ts::ShapeType::kMesh;
              const auto it = model.mesh_paths.find(m->filename);
              item.shape.mesh_path = it != model.mesh_paths.end() ? it->second : m->filename;
              item.shape.scale = Eigen::Vector3d(m->scale.x, m->scale.y, m->scale.z);
              break;
            }
            case urdf::Geometry::BOX: {
              const auto* b = static_cast<const urdf::Box*>(visual->geometry.get());
              item.shape.type = ts::ShapeType::kBox;
              item.shape.size = Eigen::Vector3d(b->dim.x, b->dim.y, b->dim.z);
              break;
            }
            case urdf::Geometry::CYLINDER: {
              const auto* c = static_cast<const urdf::Cylinder*>(visual->geometry.get());
              item.shape.type = ts::ShapeType::kCylinder;
              item.shape.radius = c->radius;
              item.shape.length = c->length;
              break;
            }
            case urdf::Geometry::SPHERE: {
              const auto* s = static_cast<const urdf::Sphere*>(visual->geometry.get());
              item.shape.type = ts::ShapeType::kSphere;
              item.shape.radius = s->radius;
              break;
            }
          }
          if (auto g = ts::findGazeboMaterial(gz)) {
            item.material = g->material;
          } else if (visual->material) {
            const auto& c = visual->material->color;
            item.material.ambient = item.material.diffuse = Eigen::Vector4f(c.r, c.g, c.b, c.a);
          }
          scene->items.push_back(item);
        }
        for (const auto& joint : link->child_joints) {
          const auto child = model.urdf->getLink(joint->child_link_name);
          visit(child, X * toIsometry(joint->parent_to_joint_origin_transform));
        }
      };
  visit(model.urdf->getRoot(), Eigen::Isometry3d::Identity());
  return X_ML;
}

const ts::SensorSpec* findSensor(const ts::RobotModel& model, const std::string& type) {
  for (const auto& kv : model.ext.links) {
    for (const auto& s : kv.second.sensors) {
      if (s.type == type) return &s;
    }
  }
  return nullptr;
}

// Wall-clock and process CPU time (all threads, llvmpipe's included) per frame, in ms. On a
// shared machine the CPU time is the steadier number.
struct Timing {
  double wall_ms = 0.0;
  double cpu_ms = 0.0;
};

template <typename F>
Timing msPerFrame(int frames, F&& render) {
  render();  // warm-up: targets, buffers
  const std::clock_t c0 = std::clock();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < frames; ++i) render();
  const auto t1 = std::chrono::steady_clock::now();
  const std::clock_t c1 = std::clock();
  return {std::chrono::duration<double, std::milli>(t1 - t0).count() / frames,
          1000.0 * (c1 - c0) / CLOCKS_PER_SEC / frames};
}


// ---- --cost-table -------------------------------------------------------------------------
// CPU (all threads of the process, llvmpipe's included) and wall time per frame, the median of
// kRounds rounds of `frames` frames, with the frame's parts from the renderer's own profile
// rows (draw up to glFinish, glReadPixels: wall time) and its draw statistics.
struct Cost {
  double cpu_ms = 0.0, wall_ms = 0.0, draw_ms = 0.0, read_ms = 0.0;
  ts::Renderer::FrameStats stats;
};

constexpr int kRounds = 5;

template <typename F>
Cost measureCost(ts::Renderer& renderer, int frames, F&& render) {
  ts::StepProfile profile;
  renderer.setProfile(&profile);
  render();  // warm-up: targets, programs, textures
  std::vector<double> cpu, wall, draw, read;
  for (int r = 0; r < kRounds; ++r) {
    profile.reset();
    const std::clock_t c0 = std::clock();
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) render();
    const auto t1 = std::chrono::steady_clock::now();
    const std::clock_t c1 = std::clock();
    cpu.push_back(1000.0 * (c1 - c0) / CLOCKS_PER_SEC / frames);
    wall.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count() / frames);
    double d = 0.0, rb = 0.0;
    for (const auto& f : profile.figures()) {
      if (f.name.find("GL draw") != std::string::npos && f.calls) d = 1000.0 * f.seconds / f.calls;
      if (f.name.find("glReadPixels") != std::string::npos && f.calls) rb = 1000.0 * f.seconds / f.calls;
    }
    draw.push_back(d);
    read.push_back(rb);
  }
  renderer.setProfile(nullptr);
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  Cost c;
  c.cpu_ms = median(cpu);
  c.wall_ms = median(wall);
  c.draw_ms = median(draw);
  c.read_ms = median(read);
  c.stats = renderer.lastFrameStats();
  return c;
}

void printCostHeader() {
  std::printf("| frame | triangles | draw calls | programs | CPU ms | wall ms | draw to glFinish ms | glReadPixels ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
}

void printCost(const std::string& what, const Cost& c) {
  std::printf("| %s | %zu | %d | %d | %.2f | %.2f | %.2f | %.2f |\n", what.c_str(), c.stats.triangles,
              c.stats.draw_calls, c.stats.program_switches, c.cpu_ms, c.wall_ms, c.draw_ms, c.read_ms);
}

// The scene with every mesh item replaced by the box of its bounds (same pose and material).
ts::Scene meshesAsBoxes(const ts::Scene& in) {
  ts::Scene out = in;
  for (auto& item : out.items) {
    if (!item.visual || item.shape.type != ts::ShapeType::kMesh) continue;
    const auto mesh = ts::meshOf(item.shape);
    if (mesh->triangleCount() == 0) continue;
    const Eigen::Vector3d lo = mesh->boundsMin().cast<double>(), hi = mesh->boundsMax().cast<double>();
    item.X_BS = item.X_BS * Eigen::Translation3d(0.5 * (lo + hi));
    item.shape = ts::Shape{};
    item.shape.type = ts::ShapeType::kBox;
    item.shape.size = (hi - lo).cwiseMax(Eigen::Vector3d::Constant(1e-3));
  }
  return out;
}

struct Seed {
  const ts::Scene* scene;
  const ts::Scene* lane;
  const ts::Scene* lane_untextured;
  ts::CameraSensor* camera;
  ts::DepthCameraSensor* depth;
  Eigen::Isometry3d X_W_cam, X_W_rs;
};

// One line for the parent's thread table: camera and real_sense render CPU/wall ms (this
// process's LP_NUM_THREADS).
int threadsProbe(ts::Renderer& renderer, const Seed& seed, int frames) {
  const Cost cam = measureCost(renderer, frames, [&] { seed.camera->render(*seed.scene, seed.X_W_cam); });
  const Cost rs = measureCost(renderer, frames, [&] {
    seed.depth->render(*seed.scene, seed.X_W_rs, {true, true, false});
  });
  std::printf("%.2f %.2f %.2f %.2f\n", cam.cpu_ms, cam.wall_ms, rs.cpu_ms, rs.wall_ms);
  return 0;
}

int costTable(ts::Renderer& renderer, const Seed& seed, int frames, const std::string& self,
              const std::string& world_path) {
  const ts::Scene& scene = *seed.scene;
  const ts::CameraIntrinsics K_cam = seed.camera->config().intrinsics();
  const ts::CameraIntrinsics K_rs = seed.depth->config().camera.intrinsics();
  const Eigen::Isometry3d X_WC_cam = seed.X_W_cam * seed.camera->config().X_LS;
  const Eigen::Isometry3d X_WC_rs = seed.X_W_rs * seed.depth->config().camera.X_LS;
  std::vector<uint8_t> rgb(static_cast<std::size_t>(std::max(K_cam.width * K_cam.height, 1600 * 1600)) * 3);
  std::vector<float> depth(static_cast<std::size_t>(K_rs.width) * K_rs.height);

  ts::Scene empty = scene;
  empty.items.clear();
  empty.ground_plane = false;
  ts::Scene ground_only = empty;
  ground_only.ground_plane = scene.ground_plane;
  ts::Scene no_ground = scene;
  no_ground.ground_plane = false;
  const ts::Scene boxes = meshesAsBoxes(scene);
  // Looking straight up from the camera: every item's triangles are set up and clipped away,
  // only the sky is filled.
  Eigen::Isometry3d X_WC_up = X_WC_cam;
  X_WC_up.linear() = Eigen::AngleAxisd(-M_PI / 2, Eigen::Vector3d::UnitY()).toRotationMatrix();

  auto view = [&](const ts::Scene& s, const Eigen::Isometry3d& X, const ts::CameraIntrinsics& K, bool with_depth) {
    return measureCost(renderer, frames, [&] {
      renderer.renderView(s, X, K, rgb.data(), with_depth ? depth.data() : nullptr);
    });
  };
  char cam_name[64], rs_name[64];
  std::snprintf(cam_name, sizeof(cam_name), "camera1 %dx%d", K_cam.width, K_cam.height);
  std::snprintf(rs_name, sizeof(rs_name), "real_sense %dx%d", K_rs.width, K_rs.height);

  std::printf("\n### Per frame and per triangle (%s)\n\n", world_path.c_str());
  printCostHeader();
  for (int which = 0; which < 2; ++which) {
    const bool cam = which == 0;
    const ts::CameraIntrinsics& K = cam ? K_cam : K_rs;
    const Eigen::Isometry3d& X = cam ? X_WC_cam : X_WC_rs;
    const std::string n = cam ? std::string(cam_name) + " colour" : std::string(rs_name) + " colour + depth";
    printCost(n + ", empty scene (clear, set-up, read-back)", view(empty, X, K, !cam));
    printCost(n + ", ground plane only", view(ground_only, X, K, !cam));
    printCost(n + ", items only (no ground plane)", view(no_ground, X, K, !cam));
    printCost(n + ", seed scene", view(scene, X, K, !cam));
    printCost(n + ", seed scene, meshes as their bounding boxes", view(boxes, X, K, !cam));
    if (cam) printCost(n + ", seed scene seen from below (all clipped, sky filled)", view(scene, X_WC_up, K, false));
    renderer.setFlatShadingProbe(true);
    printCost(n + ", seed scene, flat shading probe", view(scene, X, K, !cam));
    renderer.setFlatShadingProbe(false);
    if (!cam) {
      printCost(n.substr(0, n.find(" colour")) + " colour only, seed scene", view(scene, X, K, false));
    }
  }
  printCost(std::string(cam_name) + " sensor (render + noise + format)", measureCost(renderer, frames, [&] {
              seed.camera->render(scene, seed.X_W_cam);
            }));
  printCost(std::string(rs_name) + " sensor (render + depth range; no noise in the seed)", measureCost(renderer, frames, [&] {
              seed.depth->render(scene, seed.X_W_rs, {true, true, false});
            }));

  {
    // The camera's noise on its own (ImageNoise on a rendered frame, every frame anew).
    const ts::CameraConfig& cc = seed.camera->config();
    ts::ImageNoise noise(cc.noise_mean, cc.noise_stddev, 1);
    std::vector<uint8_t> frame(static_cast<std::size_t>(cc.width) * cc.height * 3);
    renderer.renderView(scene, X_WC_cam, K_cam, frame.data());
    std::vector<uint8_t> work = frame;
    const int reps = 5 * frames;
    std::vector<double> cpu;
    for (int r = 0; r < kRounds; ++r) {
      const std::clock_t c0 = std::clock();
      for (int i = 0; i < reps; ++i) {
        std::copy(frame.begin(), frame.end(), work.begin());
        noise.apply(work.data(), static_cast<std::size_t>(cc.width) * cc.height, 3);
      }
      cpu.push_back(1000.0 * (std::clock() - c0) / CLOCKS_PER_SEC / reps);
    }
    std::sort(cpu.begin(), cpu.end());
    std::printf("| %s noise alone (gaussian, stddev %.3g; with a copy of the frame) | | | | %.2f | | | |\n",
                cam_name, cc.noise_stddev, cpu[cpu.size() / 2]);
  }

  std::printf("\n### Per pixel: %s's view at other sizes (same field of view), seed scene\n\n", cam_name);
  std::printf("| size | pixels | CPU ms | wall ms | CPU ns per pixel |\n|---|---|---|---|---|\n");
  for (const int side : {200, 400, 800, 1131, 1600}) {
    ts::CameraIntrinsics K = K_cam;
    const double s = static_cast<double>(side) / K_cam.width;
    K.width = K.height = side;
    K.fx *= s, K.fy *= s;
    K.cx = (K_cam.cx + 0.5) * s - 0.5;
    K.cy = (K_cam.cy + 0.5) * s - 0.5;
    const Cost c = view(scene, X_WC_cam, K, false);
    std::printf("| %dx%d | %d | %.2f | %.2f | %.1f |\n", side, side, side * side, c.cpu_ms, c.wall_ms,
                1e6 * c.cpu_ms / (side * side));
  }

  std::printf("\n### Shading and textures: lane_track (textured floor)\n\n");
  printCostHeader();
  printCost(std::string(cam_name) + ", textured", view(*seed.lane, X_WC_cam, K_cam, false));
  printCost(std::string(cam_name) + ", texture taken off", view(*seed.lane_untextured, X_WC_cam, K_cam, false));
  renderer.setFlatShadingProbe(true);
  printCost(std::string(cam_name) + ", flat shading probe", view(*seed.lane, X_WC_cam, K_cam, false));
  renderer.setFlatShadingProbe(false);
  printCost(std::string(rs_name) + " colour + depth, textured", view(*seed.lane, X_WC_rs, K_rs, true));
  printCost(std::string(rs_name) + " colour + depth, texture taken off",
            view(*seed.lane_untextured, X_WC_rs, K_rs, true));

  std::printf("\n### llvmpipe's rasteriser threads (LP_NUM_THREADS; each row its own process), seed scene\n\n");
  std::printf("| LP_NUM_THREADS | %s sensor CPU ms | wall ms | %s sensor CPU ms | wall ms |\n|---|---|---|---|---|\n",
              cam_name, rs_name);
  for (const char* t : {"0", "1", "2", "3", "4"}) {
    const std::string cmd = "LP_NUM_THREADS=" + std::string(t) + " '" + self + "' --threads-probe --frames " +
                            std::to_string(frames) + " --world '" + world_path + "' 2>/dev/null";
    FILE* p = ::popen(cmd.c_str(), "r");
    double v[4] = {0, 0, 0, 0};
    char line[512];
    bool ok = false;
    while (p && std::fgets(line, sizeof(line), p)) {
      ok = std::sscanf(line, "%lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3]) == 4 || ok;
    }
    const int status = p ? ::pclose(p) : -1;
    if (!ok || status != 0) {
      std::printf("| %s | failed (%s) | | | |\n", t, cmd.c_str());
      continue;
    }
    std::printf("| %s | %.2f | %.2f | %.2f | %.2f |\n", t, v[0], v[1], v[2], v[3]);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  int frames = 100;
  std::string world_path = std::string(TIANRACER_SIM_WORLDS_DIR) + "/racetrack.world";
  std::string png_dir = "/tmp";
  bool cost_table = false, threads_probe = false;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--cost-table") {
      cost_table = true;
      --i;
      continue;
    }
    if (a == "--threads-probe") {
      threads_probe = true;
      --i;
      continue;
    }
    if (i + 1 >= argc && (a == "--frames" || a == "--world" || a == "--png-dir")) {
      std::cerr << "render_bench: " << a << " needs a value\n";
      return 2;
    }
    if (a == "--frames") frames = std::atoi(argv[i + 1]);
    else if (a == "--world") world_path = argv[i + 1];
    else if (a == "--png-dir") png_dir = argv[i + 1];
    else {
      std::cerr << "usage: render_bench [--cost-table] [--frames N] [--world PATH] [--png-dir DIR]\n";
      return 2;
    }
  }
  auto warn = [](const std::string& w) { std::cerr << "warning: " << w << "\n"; };

  ts::Scene scene;
  ts::WorldLoadOptions wopt;
  wopt.warn = warn;
  const ts::WorldDescription world = ts::loadWorldFile(world_path, wopt);
  ts::addToScene(world, scene);

  // xacro resolves $(find tianracer_description) through ROS_PACKAGE_PATH.
  const char* rpp = std::getenv("ROS_PACKAGE_PATH");
  const std::string source_space = std::string(TIANRACER_DESCRIPTION_DIR) + "/..";
  ::setenv("ROS_PACKAGE_PATH", (source_space + (rpp ? ":" + std::string(rpp) : "")).c_str(), 1);
  ts::LoadOptions lopt;
  lopt.warn = warn;
  lopt.resolver.find_package = [](const std::string& pkg) {
    return pkg == "tianracer_description" ? std::string(TIANRACER_DESCRIPTION_DIR) : std::string();
  };
  const ts::RobotModel robot = ts::loadRobotModelFile(
      std::string(TIANRACER_DESCRIPTION_DIR) + "/urdf/tianracer_description.xacro", lopt);
  Eigen::Isometry3d X_WM = Eigen::Isometry3d::Identity();
  X_WM.translation().z() = 0.0095;  // base_link above the ground with the wheels on it
  std::map<std::string, int> bodies;
  const auto X_ML = addRobot(robot, X_WM, &scene, &bodies);

  const ts::SensorSpec* cam_spec = findSensor(robot, "camera");
  const ts::SensorSpec* depth_spec = findSensor(robot, "depth");
  if (cam_spec == nullptr || depth_spec == nullptr) {
    std::cerr << "the robot has no camera or depth sensor\n";
    return 1;
  }
  ts::Renderer renderer(warn);
  ts::CameraSensor camera(ts::parseCameraConfig(*cam_spec, warn), renderer);
  ts::DepthCameraSensor depth(ts::parseDepthCameraConfig(*depth_spec, warn), renderer);
  const Eigen::Isometry3d X_W_cam = X_WM * X_ML.at(cam_spec->link);
  const Eigen::Isometry3d X_W_rs = X_WM * X_ML.at(depth_spec->link);

  std::size_t triangles = 0;
  for (const auto& item : scene.items) {
    if (item.visual && item.shape.type == ts::ShapeType::kMesh) {
      triangles += ts::meshOf(item.shape)->triangleCount();
    }
  }
  const char* threads = std::getenv("LP_NUM_THREADS");
  if (frames <= 0) {
    std::cerr << "render_bench: --frames must be > 0\n";
    return 2;
  }
  // The lane track: the same robot and cameras, with and without its floor texture.
  ts::Scene track;
  ts::addToScene(ts::loadWorldFile(std::string(TIANRACER_SIM_WORLDS_DIR) + "/lane_track.world", wopt), track);
  std::map<std::string, int> track_bodies;
  addRobot(robot, X_WM, &track, &track_bodies);
  ts::Scene untextured = track;
  std::size_t textured_items = 0;
  for (auto& item : untextured.items) {
    textured_items += !item.material.texture.empty();
    item.material.texture.clear();
  }
  const Seed seed{&scene, &track, &untextured, &camera, &depth, X_W_cam, X_W_rs};
  if (threads_probe) return threadsProbe(renderer, seed, frames);

  std::printf("%s\nworld %s: %zu bodies, %zu items (%zu mesh triangles); LP_NUM_THREADS=%s\n",
              renderer.glInfo().c_str(), world.name.c_str(), scene.bodies.size(), scene.items.size(),
              triangles, threads ? threads : "(unset)");
  if (cost_table) {
    std::printf("median of %d rounds of %d frames each\n", kRounds, frames);
    char self[4096];
    const ssize_t n = ::readlink("/proc/self/exe", self, sizeof(self) - 1);
    if (n <= 0) {
      std::cerr << "render_bench: cannot read /proc/self/exe\n";
      return 1;
    }
    self[n] = '\0';
    return costTable(renderer, seed, frames, self, world_path);
  }

  const Timing cam = msPerFrame(frames, [&] { camera.render(scene, X_W_cam); });
  const Timing rs = msPerFrame(frames, [&] { depth.render(scene, X_W_rs); });
  const Timing rs_depth = msPerFrame(frames, [&] { depth.render(scene, X_W_rs, {false, true, false}); });
  std::printf("                                      wall ms/frame  cpu ms/frame\n");
  std::printf("camera 800x800 colour+noise            %8.2f      %8.2f\n", cam.wall_ms, cam.cpu_ms);
  std::printf("depth 640x480 colour+depth+cloud       %8.2f      %8.2f\n", rs.wall_ms, rs.cpu_ms);
  std::printf("depth 640x480 depth image only         %8.2f      %8.2f\n", rs_depth.wall_ms, rs_depth.cpu_ms);
  std::printf("seed cameras at rated rates (30 + 20 Hz): %.0f ms wall, %.0f ms cpu per simulated second\n",
              30 * cam.wall_ms + 20 * rs.wall_ms, 30 * cam.cpu_ms + 20 * rs.cpu_ms);

  const Timing cam_tex = msPerFrame(frames, [&] { camera.render(track, X_W_cam); });
  const Timing cam_plain = msPerFrame(frames, [&] { camera.render(untextured, X_W_cam); });
  const Timing rs_tex = msPerFrame(frames, [&] { depth.render(track, X_W_rs); });
  const Timing rs_plain = msPerFrame(frames, [&] { depth.render(untextured, X_W_rs); });
  std::printf("lane_track (%zu textured item(s)), with / without texture:\n", textured_items);
  std::printf("camera 800x800 colour+noise            %8.2f / %5.2f  %8.2f / %5.2f\n", cam_tex.wall_ms,
              cam_plain.wall_ms, cam_tex.cpu_ms, cam_plain.cpu_ms);
  std::printf("depth 640x480 colour+depth+cloud       %8.2f / %5.2f  %8.2f / %5.2f\n", rs_tex.wall_ms,
              rs_plain.wall_ms, rs_tex.cpu_ms, rs_plain.cpu_ms);

  // Pictures.
  camera.render(track, X_W_cam);
  ts::writePng(png_dir + "/render_lane_track_camera.png", camera.image().data(), camera.config().width,
               camera.config().height, camera.channels());
  ts::CameraIntrinsics chase = ts::CameraIntrinsics::fromHorizontalFov(960, 640, 1.0, 0.02, 100.0);
  Eigen::Isometry3d X_WChase = Eigen::Translation3d(-0.55, -0.35, 0.35) *
                               Eigen::AngleAxisd(0.55, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(0.45, Eigen::Vector3d::UnitY());
  std::vector<uint8_t> rgb(960 * 640 * 3);
  renderer.renderView(scene, X_WChase, chase, rgb.data());
  ts::writePng(png_dir + "/render_chase.png", rgb.data(), 960, 640, 3);
  camera.render(scene, X_W_cam);
  ts::writePng(png_dir + "/render_camera.png", camera.image().data(), camera.config().width,
               camera.config().height, camera.channels());
  depth.render(scene, X_W_rs);
  const auto& dc = depth.config().camera;
  ts::writePng(png_dir + "/render_real_sense_rgb.png", depth.image().data(), dc.width, dc.height, depth.channels());
  ts::writeDepthPng(png_dir + "/render_real_sense_depth.png", depth.depth().data(), dc.width, dc.height,
                    depth.config().point_cloud_cutoff, depth.config().point_cloud_cutoff_max);
  std::printf("wrote %s/render_{chase,camera,real_sense_rgb,real_sense_depth,lane_track_camera}.png\n",
              png_dir.c_str());
  return 0;
}
