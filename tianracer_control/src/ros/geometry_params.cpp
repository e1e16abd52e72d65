#include "tianracer_control/ros/geometry_params.h"

#include <cmath>

#include <ros/console.h>
#include <ros/package.h>

namespace tianracer_control {

bool getNumberParam(const ros::NodeHandle& pnh, const std::string& key, double* value) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(key, v)) return false;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    *value = static_cast<double>(v);
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) {
    *value = static_cast<int>(v);
  } else {
    throw AckermannError("parameter " + pnh.resolveName(key) + " must be a number, got '" +
                         v.toXml() + "'");
  }
  return true;
}

AckermannJointNames loadJointNames(const ros::NodeHandle& pnh) {
  AckermannJointNames j;
  pnh.param("left_steering_hinge_joint", j.left_hinge, j.left_hinge);
  pnh.param("right_steering_hinge_joint", j.right_hinge, j.right_hinge);
  pnh.param("left_rear_wheel_joint", j.left_rear_wheel, j.left_rear_wheel);
  pnh.param("right_rear_wheel_joint", j.right_rear_wheel, j.right_rear_wheel);
  return j;
}

AckermannGeometry loadAckermannGeometry(const ros::NodeHandle& nh, const ros::NodeHandle& pnh,
                                        const AckermannJointNames& joints) {
  std::map<std::string, double> params;
  for (const std::string& key : geometryKeys()) {
    double v;
    if (getNumberParam(pnh, key, &v)) params[key] = v;
  }

  UrdfGeometry urdf;
  bool have_urdf = false;
  if (params.size() < geometryKeys().size()) {
    const std::string param_name = pnh.param<std::string>("robot_description_param",
                                                          "robot_description");
    const std::string base_frame = pnh.param<std::string>("base_frame", "base_link");
    std::string key, xml;
    if (nh.searchParam(param_name, key) && nh.getParam(key, xml)) {
      urdf = geometryFromUrdf(xml, joints, base_frame, [](const std::string& uri) {
        return resolveMeshUri(uri, [](const std::string& pkg) { return ros::package::getPath(pkg); });
      });
      have_urdf = true;
      ROS_INFO_STREAM("geometry: reading " << key);
    } else {
      ROS_WARN_STREAM("geometry: no " << param_name << " parameter found from "
                                      << nh.getNamespace()
                                      << "; geometry from parameters and defaults only");
    }
  }

  const ResolvedGeometry resolved = resolveGeometry(params, have_urdf ? &urdf : nullptr);
  for (const std::string& w : resolved.warnings) ROS_WARN_STREAM("geometry: " << w);
  for (const auto& kv : resolved.values) {
    ROS_INFO_STREAM("geometry: " << kv.first << " = " << kv.second.value << " ("
                                 << kv.second.source << ")");
  }
  const AckermannGeometry& g = resolved.geometry;
  const double left = maxBicycleAngleLeft(g), right = maxBicycleAngleRight(g);
  ROS_INFO_STREAM("geometry: largest bicycle steering angle " << left << " rad left, " << right
                  << " rad right; minimum turning radius " << g.wheelbase / std::tan(left)
                  << " m left, " << g.wheelbase / std::tan(right)
                  << " m right (rear axle midpoint)");
  return resolved.geometry;
}

}  // namespace tianracer_control
