#include "tianracer_sim/ros/controller_params.h"

#include <algorithm>

#include <ros/param.h>
#include <XmlRpcValue.h>

#include <tianracer_control/ros/controller_adapter.h>

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

std::vector<std::string> RosControlParams::list(const std::string& ns) const {
  return listControllers(ros::NodeHandle(ns));
}

std::vector<tianracer_control::ControllerSpec> RosControlParams::load(
    const std::string& ns, const std::vector<std::string>& names) const {
  return tianracer_control::loadControllerSpecs(ros::NodeHandle(ns), names);
}

std::string RosControlParams::resolve(const std::string& ns) const {
  return ros::NodeHandle(ns).getNamespace();
}

}  // namespace tianracer_sim
