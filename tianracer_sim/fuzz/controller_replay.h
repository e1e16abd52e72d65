// The promises of the controller set-up, checked on one controller YAML: the fuzz harness
// (fuzz_controllers.cpp) and the replay of the regression corpus
// (test/unit/test_simulator_controller_fuzz_regressions.cpp) run the same code, so that CI, which
// has no libFuzzer, replays what the fuzzer found. Header-only; needs TEST_DATA_DIR and
// TIANRACER_DESCRIPTION_DIR defined.
//
// The YAML goes through the one robot set-up the node and the Python environment share
// (YamlControlParams, setUpRobot); its controllers are built on a robot (Simulation::addRobot) on
// the ground plane and stepped kControllerSteps times, each controller that takes a command given
// a new one every 50 steps. Either that ends in InputError (ControllerError, ModelError,
// PhysicsError: the caller catches it), or every base pose, joint position, velocity and command
// stays finite; anything else is a broken promise.
#ifndef TIANRACER_SIM_FUZZ_CONTROLLER_REPLAY_H
#define TIANRACER_SIM_FUZZ_CONTROLLER_REPLAY_H

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/simulator/robot_setup.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim_fuzz {

constexpr int kControllerSteps = 300;

/// The robots a YAML is tried on: 't' the tianracer (xacro expanded once), 's'
/// steerbot_control.urdf, anything else diffbot_control.urdf (test/data/urdf).
inline const tianracer_sim::RobotModel& controllerReplayRobot(char pick) {
  using namespace tianracer_sim;
  const auto options = [] {
    LoadOptions o;
    o.resolver.find_package = [](const std::string& pkg) {
      return pkg == "tianracer_description" ? std::string(TIANRACER_DESCRIPTION_DIR) : std::string();
    };
    o.warn = [](const std::string&) {};
    return o;
  };
  static const RobotModel diffbot =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/diffbot_control.urdf", options());
  static const RobotModel steerbot =
      loadRobotModelFile(std::string(TEST_DATA_DIR) + "/urdf/steerbot_control.urdf", options());
  static const RobotModel tianracer = [&] {
    // xacro's $(find tianracer_description) needs the package on ROS_PACKAGE_PATH.
    const char* rpp = std::getenv("ROS_PACKAGE_PATH");
    const std::string path = std::string(TIANRACER_DESCRIPTION_DIR) + "/.." +
                             (rpp ? std::string(":") + rpp : std::string());
    ::setenv("ROS_PACKAGE_PATH", path.c_str(), 1);
    return loadRobotModelFile(std::string(TIANRACER_DESCRIPTION_DIR) + "/urdf/tianracer_description.xacro",
                              options());
  }();
  return pick == 't' ? tianracer : pick == 's' ? steerbot : diffbot;
}

/// What broke ("" when nothing) running the controller YAML `yaml_file` on `model`; the commands
/// are taken in turn from the bytes of `commands` ((b - 128) / 16). Throws InputError.
inline std::string replayControllerYaml(const tianracer_sim::RobotModel& model,
                                        const std::string& yaml_file, const std::string& commands) {
  using namespace tianracer_sim;
  const WarningSink warn = [](const std::string&) {};
  YamlControlParams params(yaml_file);
  RobotSetupRequest request;
  request.control_config = yaml_file;
  const RobotSetup setup = setUpRobot(model, request, params);
  static const WorldDescription world = loadWorldString(
      "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri></include>"
      "</world></sdf>",
      "ground.world", ".");
  RobotConfig config;
  config.name = setup.name;
  config.model = model;
  config.drop_to_ground = true;
  config.controllers = setup.controllers;
  Simulation sim(physicsOptionsFor(world), warn);
  addWorldToPhysics(world, &sim.physics(), warn);
  SimRobot& r = sim.addRobot(config);
  const PhysicsRobot& body = sim.physics().robot(r.id);
  std::size_t next = 0;
  for (int k = 0; k < kControllerSteps; ++k) {
    if (k % 50 == 0) {
      for (const auto& c : r.controllers.controllers()) {
        if (!c->hasCommand()) continue;
        const auto b = commands.empty() ? 128 : static_cast<uint8_t>(commands[next++ % commands.size()]);
        c->setCommand((static_cast<int>(b) - 128) / 16.0);
      }
    }
    sim.step();
    const std::string at = " at step " + std::to_string(k + 1);
    if (!body.basePose().matrix().allFinite()) return "base pose not finite" + at;
    for (std::size_t j = 0; j < body.joints().size(); ++j) {
      if (!std::isfinite(body.jointPosition(static_cast<int>(j))) ||
          !std::isfinite(body.jointVelocity(static_cast<int>(j))))
        return "joint " + std::to_string(j) + " not finite" + at;
    }
    for (const auto& h : r.handles)
      if (!std::isfinite(h.command)) return "joint command not finite" + at;
  }
  return "";
}

}  // namespace tianracer_sim_fuzz

#endif  // TIANRACER_SIM_FUZZ_CONTROLLER_REPLAY_H
