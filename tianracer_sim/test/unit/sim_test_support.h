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

/// A YAML node as the parameter server holds it (rosparam load: ints, doubles, bools, strings).
inline tianracer_control::ParamValue toParamValue(const YAML::Node& node) {
  using tianracer_control::ParamValue;
  if (node.IsMap()) {
    ParamValue tree = ParamValue::dict();
    for (const auto& entry : node) tree[entry.first.as<std::string>()] = toParamValue(entry.second);
    return tree;
  }
  if (node.IsSequence()) {
    ParamValue::List items;
    for (const auto& item : node) items.push_back(toParamValue(item));
    return ParamValue::list(std::move(items));
  }
  int i = 0;
  double d = 0.0;
  bool b = false;
  if (YAML::convert<int>::decode(node, i)) return ParamValue(i);
  if (YAML::convert<double>::decode(node, d)) return ParamValue(d);
  if (YAML::convert<bool>::decode(node, b)) return ParamValue(b);
  return ParamValue(node.as<std::string>());
}

/// The controllers of a ros_control YAML under `ns`, as the node reads them from the
/// parameter server.
inline std::vector<tianracer_control::ControllerSpec> loadControllerYaml(const std::string& file,
                                                                        const std::string& ns) {
  std::vector<tianracer_control::ControllerSpec> specs;
  const YAML::Node root = YAML::LoadFile(file)[ns];
  for (const auto& entry : root) {
    tianracer_control::ControllerSpec spec;
    spec.name = entry.first.as<std::string>();
    spec.type = entry.second["type"].as<std::string>();
    spec.params = toParamValue(entry.second);
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
