#include "tianracer_sim/ros/params.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "tianracer_sim/sim/simulation.h"

namespace tianracer_sim {

namespace {

std::optional<double> optionalDouble(const ros::NodeHandle& pnh, const std::string& key) {
  if (!pnh.hasParam(key)) return std::nullopt;
  return getDouble(pnh, key, 0.0);
}

}  // namespace

NodeParams readNodeParams(const ros::NodeHandle& pnh) {
  NodeParams p;
  pnh.param<std::string>("world", p.world, p.world);
  pnh.param("strict_world", p.strict_world, p.strict_world);
  p.max_step_size = optionalDouble(pnh, "max_step_size");
  p.real_time_factor = optionalDouble(pnh, "real_time_factor");
  pnh.param("paused", p.paused, p.paused);
  p.clock_rate = getDouble(pnh, "clock_rate", p.clock_rate);
  p.ground_truth_rate = getDouble(pnh, "ground_truth_rate", p.ground_truth_rate);
  pnh.param("seed", p.seed, p.seed);
  p.status_period = getDouble(pnh, "status_period", p.status_period);
  pnh.param("diagnostics", p.diagnostics, p.diagnostics);
  p.gazebo_states_rate = optionalDouble(pnh, "gazebo_states_rate");
  // gazebo_ros's ~enable_ros_network (its node is /gazebo: the gzserver stand-in's name).
  pnh.param("enable_ros_network", p.enable_ros_network, p.enable_ros_network);
  pnh.param("step_services", p.step_services, p.step_services);
  pnh.param<std::string>("gazebo_namespace", p.gazebo_namespace, p.gazebo_namespace);
  return p;
}

void checkPace(double max_step_size, double real_time_factor) {
  if (!(max_step_size > 0.0 && max_step_size <= 0.1)) {
    throw std::runtime_error("parameter ~max_step_size must be in (0, 0.1] s, got " +
                             std::to_string(max_step_size));
  }
  if (!(real_time_factor >= 0.0) || !std::isfinite(real_time_factor)) {
    throw std::runtime_error("parameter ~real_time_factor must be >= 0 (0 = as fast as possible), got " +
                             std::to_string(real_time_factor));
  }
}

double getDouble(const ros::NodeHandle& pnh, const std::string& key, double fallback) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(key, v)) return fallback;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw std::runtime_error("parameter " + pnh.resolveName(key) + " must be a number, got " +
                           v.toXml());
}

std::vector<std::string> getNameList(const ros::NodeHandle& pnh, const std::string& key,
                                     bool* given) {
  std::vector<std::string> names;
  XmlRpc::XmlRpcValue v;
  *given = pnh.getParam(key, v);
  if (!*given) return names;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < v.size(); ++i) {
      if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString) {
        throw std::runtime_error("parameter " + pnh.resolveName(key) + " must list names");
      }
      names.push_back(static_cast<std::string>(v[i]));
    }
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    std::istringstream in(static_cast<std::string>(v));
    for (std::string n; in >> n;) names.push_back(n);
  } else {
    throw std::runtime_error("parameter " + pnh.resolveName(key) +
                             " must be a list or a space-separated string");
  }
  return names;
}

Eigen::Isometry3d getSpawnPose(const ros::NodeHandle& rp, bool* auto_z) {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  const double roll = getDouble(rp, "roll", 0.0), pitch = getDouble(rp, "pitch", 0.0),
               yaw = getDouble(rp, "yaw", 0.0);
  X_WB.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  X_WB.translation() = Eigen::Vector3d(getDouble(rp, "x", 0.0), getDouble(rp, "y", 0.0), 0.0);
  *auto_z = true;
  XmlRpc::XmlRpcValue zv;
  if (rp.getParam("z", zv) && !(zv.getType() == XmlRpc::XmlRpcValue::TypeString &&
                                  static_cast<std::string>(zv) == "auto")) {
    X_WB.translation().z() = getDouble(rp, "z", 0.0);
    *auto_z = false;
  }
  if (const std::string bad = checkModelState(X_WB, Twist()); !bad.empty())
    throw std::runtime_error("spawn pose (~x ~y ~z ~roll ~pitch ~yaw): " + bad);
  return X_WB;
}

}  // namespace tianracer_sim
