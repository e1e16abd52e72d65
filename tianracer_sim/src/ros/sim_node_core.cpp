// The node's core from its ~ parameters (ros/sim_node_core.h): the world file, the Simulator on
// it, the step profile.
#include "tianracer_sim/ros/sim_node_core.h"

#include <chrono>

#include <ros/package.h>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/ros/robot_bridge.h"

namespace tianracer_sim {

void warnOnceOnRosout(const std::string& text) {
  static WarnOnce once([](const std::string& w) { ROS_WARN_STREAM(w); });
  once(text);
}

NodeProfileRows nodeProfileRows(StepProfile& p) {
  NodeProfileRows rows;
  rows.step = p.row(StepProfile::kStep);
  rows.callbacks = p.row(std::string(StepProfile::kBetweenSteps) + "callbacks (commands, services)");
  rows.status = p.row(std::string(StepProfile::kBetweenSteps) + "status and /diagnostics");
  rows.commands = p.row("ros: commands in (controllers' topics, efforts, wrenches)");
  p.row(StepProfile::kControllers);
  p.row(StepProfile::kBullet);
  p.row(StepProfile::kContactScan);
  rows.contact_msgs = p.row("ros: contact messages");
  rows.clock = p.row("ros: /clock");
  for (const char* name : RobotBridge::kProfileRows) p.row(name);
  rows.lockstep = p.row("lockstep: waiting for replies and ticks");
  rows.gazebo_states = p.row("ros: /gazebo/model_states and link_states");
  return rows;
}

std::unique_ptr<StepProfile> makeNodeProfile() {
  auto profile = std::make_unique<StepProfile>();
  nodeProfileRows(*profile);
  return profile;
}

SimNodeCore makeSimNodeCore(const ros::NodeHandle& pnh) {
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now();
  SimNodeCore core;
  const auto mark = [&](const std::string& what) {
    const auto now = Clock::now();
    core.startup.emplace_back(what, std::chrono::duration<double, std::milli>(now - last).count());
    last = now;
  };
  core.params = readNodeParams(pnh);
  const NodeParams& params = core.params;
  bool profile = false;
  pnh.param("profile", profile, false);
  if (profile) core.profile = makeNodeProfile();

  // The world: a shipped name or a .world path. Its <physics> gives the step and gravity.
  WorldLoadOptions& world_options = core.world_options;
  world_options.warn = warnOnceOnRosout;
  // A model or mesh that cannot be used is an error and the rest loads, as in Gazebo;
  // ~strict_world:=true stops instead (CI).
  world_options.error = [](const std::string& e) { ROS_ERROR_STREAM(e); };
  world_options.strict = params.strict_world;
  world_options.find_package = [](const std::string& pkg) { return ros::package::getPath(pkg); };
  WorldDescription world = loadWorldFile(
      resolveWorld(params.world, ros::package::getPath("tianracer_sim") + "/worlds"), world_options);
  mark("world file and its meshes");

  SimulatorOptions options;
  options.max_step_size = params.max_step_size.value_or(worldTimeStep(world));
  core.real_time_factor = params.real_time_factor.value_or(world.physics.real_time_factor);
  checkPace(options.max_step_size, core.real_time_factor);
  options.seed = static_cast<std::uint64_t>(params.seed);
  options.log.info = [](const std::string& m) { ROS_INFO_STREAM(m); };
  options.log.warn = warnOnceOnRosout;
  options.log.error = [](const std::string& m) { ROS_ERROR_STREAM(m); };
  options.log.frame_error = [](const std::string& m) { ROS_ERROR_STREAM_THROTTLE(10.0, m); };
  options.profile = core.profile.get();
  core.sim = std::make_unique<Simulator>(std::move(world), std::move(options));
  mark("simulator (the world's physics, scene, sensors)");
  core.sim->setPaused(params.paused);
  // The pace as Gazebo holds it (set_physics_properties' max_update_rate changes it).
  PhysicsProperties physics = core.sim->properties().physicsProperties();
  physics.max_update_rate = core.real_time_factor / core.sim->dt();
  core.sim->properties().setPhysicsProperties(physics);
  return core;
}

}  // namespace tianracer_sim
