#include "tianracer_sim/ros/controller_params.h"

#include <algorithm>

#include <ros/param.h>
#include <XmlRpcValue.h>

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

}  // namespace tianracer_sim
