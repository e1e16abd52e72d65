#include "tianracer_sim/ros/params.h"

#include <sstream>
#include <stdexcept>

#include "tianracer_sim/sim/simulation.h"

namespace tianracer_sim {

std::string trimSlashes(std::string s) {
  while (!s.empty() && s.front() == '/') s.erase(s.begin());
  while (!s.empty() && s.back() == '/') s.pop_back();
  return s;
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
