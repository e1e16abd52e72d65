#include "tianracer_sim/ros/controller_params.h"

#include <algorithm>

#include <ros/console.h>
#include <ros/param.h>
#include <XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

namespace tianracer_sim {

std::vector<std::string> listControllers(const ros::NodeHandle& ns) {
  std::vector<std::string> names;
  XmlRpc::XmlRpcValue all;
  if (!ros::param::get(ns.getNamespace(), all) || all.getType() != XmlRpc::XmlRpcValue::TypeStruct) return names;
  for (auto& [key, value] : all) {
    if (value.getType() == XmlRpc::XmlRpcValue::TypeStruct && value.hasMember("type")) {
      names.push_back(key);
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

ControlConfigKeys readControlConfigKeys(const std::string& file) {
  ControlConfigKeys out;
  out.file = file;
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::Exception& e) {
    out.error = e.what();
    return out;
  }
  if (!root.IsMap()) {
    out.error = "its top level is not a dictionary";
    return out;
  }
  for (const auto& entry : root) {
    const std::string key = entry.first.as<std::string>();
    out.keys.push_back(key);
    if (!entry.second.IsMap()) continue;
    for (const auto& member : entry.second) {
      if (member.second.IsMap() && member.second["type"]) {
        out.with_controllers.push_back(key);
        break;
      }
    }
  }
  return out;
}

std::string chooseControlNamespace(const std::string& robot_ns, bool robot_ns_has_controllers,
                                   const ControlConfigKeys& config) {
  if (robot_ns_has_controllers || config.with_controllers.size() != 1) return robot_ns;
  return config.with_controllers.front();
}

std::string defaultControlNamespace(const ros::NodeHandle& rp, const std::string& robot_ns,
                                    ControlConfigKeys* config) {
  std::string file;
  if (rp.getParam("control_config", file) && !file.empty()) *config = readControlConfigKeys(file);
  const bool here = !listControllers(ros::NodeHandle(robot_ns)).empty();
  const std::string ns = chooseControlNamespace(robot_ns, here, *config);
  if (ns != robot_ns) {
    ROS_INFO_STREAM("controllers of " << robot_ns << " read from " << ros::NodeHandle(ns).getNamespace()
                    << ", the one key of " << config->file << " that defines controllers (none are "
                    << "defined under " << robot_ns << "; control_key:= picks another)");
  }
  return ns;
}

std::string noControllersWarning(const std::string& robot, const std::string& searched,
                                 const ControlConfigKeys& config) {
  std::string text = "robot '" + robot + "' has gazebo_ros_control but no controller: none is " +
                     "defined under " + searched + " (a dictionary with a 'type' key)";
  if (config.file.empty()) {
    return text + "; load the controller YAML (rosparam load) under " + searched +
           ", or give ~control_namespace";
  }
  if (!config.error.empty()) {
    return text + "; control_config " + config.file + " could not be read: " + config.error;
  }
  std::string keys;
  for (const std::string& k : config.keys) keys += (keys.empty() ? "" : ", ") + k;
  text += "; control_config " + config.file + " has the top-level keys [" + keys + "]";
  if (!config.with_controllers.empty()) {
    text += ": pass control_key:=" + config.with_controllers.front() +
            " (or key the YAML by the robot's namespace)";
  }
  return text;
}

}  // namespace tianracer_sim
