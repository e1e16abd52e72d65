// Shared fixtures of the sim-level tests: the real tianracer, its shipped controllers.
#ifndef TIANRACER_SIM_TEST_SIM_TEST_SUPPORT_H
#define TIANRACER_SIM_TEST_SIM_TEST_SUPPORT_H

#include <cstdlib>
#include <string>
#include <vector>

#include <tianracer_control/controller_yaml.h>

#include "tianracer_sim/sim/simulation.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace test {

/// base_link height at which the rear wheels (centre z 0.0225, radius 0.032) touch the ground.
constexpr double kSpawnZ = 0.0095;
constexpr double kWheelRadius = 0.032;

inline std::string descriptionDir() { return TIANRACER_DESCRIPTION_DIR; }
inline std::string repoDir() { return descriptionDir() + "/.."; }

/// The ground plane and `models` (SDF <model> elements), loaded as test.world.
inline WorldDescription groundWorld(const std::string& models = "") {
  return loadWorldString(
      "<sdf version='1.6'><world name='w'><include><uri>model://ground_plane</uri></include>" +
          models + "</world></sdf>",
      "test.world", ".");
}

/// The ground plane and a static wall 0.2 x 4 x 1 m at x = 2 (its near face at x = 1.9).
inline WorldDescription groundWithWall() {
  return groundWorld(
      "<model name='wall'><static>true</static><pose>2 0 0.5 0 0 0</pose><link name='link'>"
      "<collision name='c'><geometry><box><size>0.2 4 1</size></box></geometry></collision>"
      "<visual name='v'><geometry><box><size>0.2 4 1</size></box></geometry></visual>"
      "</link></model>");
}

/// The tianracer as the sim loads it (xacro expanded, meshes resolved in the repo).
inline RobotModel loadTianracer() {
  // xacro's $(find tianracer_description) needs the package on ROS_PACKAGE_PATH.
  const char* rpp = std::getenv("ROS_PACKAGE_PATH");
  const std::string path = repoDir() + (rpp ? std::string(":") + rpp : std::string());
  setenv("ROS_PACKAGE_PATH", path.c_str(), 1);
  LoadOptions options;
  options.resolver.find_package = [](const std::string& pkg) {
    return pkg == "tianracer_description" ? descriptionDir() : std::string();
  };
  return loadRobotModelFile(descriptionDir() + "/urdf/tianracer_description.xacro", options);
}

/// The tianracer as spawn_model adds it: named `name`, base_link at p_WB, no controllers.
inline RobotConfig tianracerAt(const Eigen::Vector3d& p_WB, const std::string& name = "tianracer") {
  RobotConfig config;
  config.name = name;
  config.model = loadTianracer();
  config.X_WB_spawn.translation() = p_WB;
  return config;
}

/// The controllers of a ros_control YAML under `ns`, as the node reads them from the
/// parameter server (tianracer_control's reader, shared with the Python simulation).
inline std::vector<tianracer_control::ControllerSpec> loadControllerYaml(const std::string& file,
                                                                        const std::string& ns) {
  return tianracer_control::loadControllerYamlFile(file, ns);
}

inline std::vector<tianracer_control::ControllerSpec> shippedControllers() {
  return loadControllerYaml(repoDir() + "/tianracer_control/config/tianracer_control.yaml",
                            "tianracer");
}

}  // namespace test
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_TEST_SIM_TEST_SUPPORT_H
