// Shared fixtures of the sim-level tests: the real tianracer, its shipped controllers.
#ifndef TIANRACER_SIM_TEST_SIM_TEST_SUPPORT_H
#define TIANRACER_SIM_TEST_SIM_TEST_SUPPORT_H

#include <cstdlib>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "tianracer_sim/sim/simulation.h"

namespace tianracer_sim {
namespace test {

inline std::string descriptionDir() { return TIANRACER_DESCRIPTION_DIR; }
inline std::string repoDir() { return descriptionDir() + "/.."; }

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

/// The controllers of a ros_control YAML under `ns`, as the node reads them from the
/// parameter server (type, joint, pid/{...}, publish_rate).
inline std::vector<tianracer_control::ControllerSpec> loadControllerYaml(const std::string& file,
                                                                        const std::string& ns) {
  std::vector<tianracer_control::ControllerSpec> specs;
  const YAML::Node root = YAML::LoadFile(file)[ns];
  for (const auto& entry : root) {
    tianracer_control::ControllerSpec spec;
    spec.name = entry.first.as<std::string>();
    const YAML::Node c = entry.second;
    spec.type = c["type"].as<std::string>();
    if (c["joint"]) spec.joint = c["joint"].as<std::string>();
    if (c["publish_rate"]) spec.publish_rate = c["publish_rate"].as<double>();
    if (c["pid"]) {
      tianracer_control::PidParams pid;
      const YAML::Node p = c["pid"];
      if (p["p"]) pid.p = p["p"].as<double>();
      if (p["i"]) pid.i = p["i"].as<double>();
      if (p["d"]) pid.d = p["d"].as<double>();
      if (p["i_clamp"]) pid.i_clamp = p["i_clamp"].as<double>();
      if (p["i_clamp_min"]) pid.i_clamp_min = p["i_clamp_min"].as<double>();
      if (p["i_clamp_max"]) pid.i_clamp_max = p["i_clamp_max"].as<double>();
      if (p["antiwindup"]) pid.antiwindup = p["antiwindup"].as<bool>();
      spec.pid = pid;
    }
    specs.push_back(spec);
  }
  return specs;
}

inline std::vector<tianracer_control::ControllerSpec> shippedControllers() {
  return loadControllerYaml(repoDir() + "/tianracer_control/config/tianracer_control.yaml",
                            "tianracer");
}

/// base_link height at which the rear wheels (centre z 0.0225, radius 0.032) touch the ground.
constexpr double kSpawnZ = 0.0095;
constexpr double kWheelRadius = 0.032;

}  // namespace test
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_TEST_SIM_TEST_SUPPORT_H
