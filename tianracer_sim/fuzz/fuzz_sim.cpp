// libFuzzer harness: a mutated URDF or SDF world built into the simulation and stepped, as
// test_sim_fuzz_regressions replays its corpus. The first byte picks the kind: 'w' a world
// (loadWorldString, addWorldToPhysics), anything else a URDF (loadRobotModel, Simulation::addRobot
// on the ground plane); the rest is the file. Each is stepped 300 times with a ray fan cast
// every 50 steps (sim_replay.h, shared with the regression replay). Loading may only end in
// InputError (and its aliases ModelError, WorldError, PhysicsError, MeshError); any other
// exception, a sanitizer report, a pose, joint position or velocity that stops being finite,
// or a NaN ray distance is a crash.
//   FUZZ_TARGETS=sim scripts/fuzz.sh [seconds]
#include <cstdint>
#include <string>

#include "fuzz_check.h"
#include "sim_replay.h"
#include "tianracer_sim/world/world.h"

namespace {

using namespace tianracer_sim;

const tianracer_sim_fuzz::PromiseCheck check{"fuzz_sim"};

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
  const std::string broken = tianracer_sim_fuzz::replayRobot(std::move(config), groundWorld(), warn);
  check(broken.empty(), broken.c_str());
}

void runWorld(const std::string& xml, const WarningSink& warn) {
  WorldLoadOptions options;
  options.warn = warn;
  options.require_meshes = false;
  const std::string broken = tianracer_sim_fuzz::replayWorld(
      loadWorldString(xml, "fuzz.world", "/nonexistent", options), warn);
  check(broken.empty(), broken.c_str());
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
