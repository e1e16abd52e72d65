// libFuzzer harness: a mutated URDF or SDF world built into the simulation and stepped, as
// test_sim_fuzz_regressions replays its corpus. The first byte picks the kind: 'w' a world
// (loadWorldString, addWorldToPhysics), anything else a URDF (loadRobotModel, Simulation::addRobot
// on the ground plane); the rest is the file. Each is stepped kSteps times with a ray fan cast
// every 50 steps. Loading may only end in InputError (and its aliases ModelError, WorldError,
// PhysicsError, MeshError); any other exception, a sanitizer report, or a pose, joint position
// or velocity that stops being finite is a crash.
//   FUZZ_TARGETS=sim scripts/fuzz.sh [seconds]
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_check.h"
#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/sim/robot_scene.h"
#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/world/world.h"

namespace {

using namespace tianracer_sim;

const tianracer_sim_fuzz::PromiseCheck check{"fuzz_sim"};
constexpr int kSteps = 300;

void checkRobot(const PhysicsRobot& r) {
  check(r.basePose().matrix().allFinite(), "base pose not finite after a step");
  for (std::size_t j = 0; j < r.joints().size(); ++j) {
    check(std::isfinite(r.jointPosition(static_cast<int>(j))), "joint position not finite");
    check(std::isfinite(r.jointVelocity(static_cast<int>(j))), "joint velocity not finite");
  }
}

void castFan(RayCaster* caster, const Scene& scene) {
  caster->update(scene);
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < 36; ++i) {
    const float a = static_cast<float>(i * M_PI / 18.0);
    dirs.emplace_back(std::cos(a), std::sin(a), -0.05f);
  }
  std::vector<float> d(dirs.size());
  caster->castRays(Eigen::Vector3d(-1.0, 0.0, 0.3), dirs, 0.0f, 30.0f, d.data());
  for (float x : d) check(!std::isnan(x), "a ray distance is NaN");
}

const WorldDescription& groundWorld() {
  static const WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri></include>"
      "</world></sdf>",
      "ground.world", ".");
  return w;
}

void runRobot(const std::string& urdf, const WarningSink& warn) {
  LoadOptions options;
  options.warn = warn;
  options.require_meshes = false;  // mesh files are fuzz_mesh's
  RobotConfig config;
  config.name = "fuzz";
  config.model = loadRobotModel(urdf, "fuzz.urdf", options);
  config.X_WB_spawn.translation() = Eigen::Vector3d(0, 0, 0.2);
  const WorldDescription& world = groundWorld();
  Simulation sim(physicsOptionsFor(world), warn);
  addWorldToPhysics(world, &sim.physics(), warn);
  Scene scene;
  addToScene(world, scene);
  SimRobot& robot = sim.addRobot(config);
  const RobotSceneBodies bodies = addRobotToScene(robot.model, robot.name, &scene);
  const PhysicsRobot& r = sim.physics().robot(robot.id);
  RayCaster caster;
  for (int k = 1; k <= kSteps; ++k) {
    sim.step();
    checkRobot(r);
    if (k % 50 == 0) {
      updateRobotScene(r, bodies, &scene);
      castFan(&caster, scene);
    }
  }
}

void runWorld(const std::string& xml, const WarningSink& warn) {
  WorldLoadOptions options;
  options.warn = warn;
  options.require_meshes = false;
  const WorldDescription world = loadWorldString(xml, "fuzz.world", "/nonexistent", options);
  Simulation sim(physicsOptionsFor(world), warn);
  addWorldToPhysics(world, &sim.physics(), warn);
  Scene scene;
  addToScene(world, scene);
  RayCaster caster;
  for (int k = 1; k <= kSteps; ++k) {
    sim.step();
    for (int b = 0; b < sim.physics().freeBodyCount(); ++b)
      if (sim.physics().hasFreeBody(b)) checkRobot(sim.physics().freeBody(b));
    if (k % 50 == 0) {
      updateFreeBodyScene(sim.physics(), &scene);
      castFan(&caster, scene);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const WarningSink warn = [](const std::string&) {};
  try {
    if (data[0] == 'w')
      runWorld(text, warn);
    else
      runRobot(text, warn);
  } catch (const InputError&) {
  }
  return 0;
}
