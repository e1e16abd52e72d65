#include "tianracer_control/ros/geometry_params.h"

#include <cmath>

#include <ros/console.h>
#include <ros/package.h>
#include <tianracer_assets/paths.h>

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

AckermannSetup loadAckermannSetup(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) {
  AckermannSetup setup;
  setup.joints = loadJointNames(pnh);
  setup.base_frame = pnh.param<std::string>("base_frame", "base_link");
  std::map<std::string, double> params;
  for (const std::string& key : geometryKeys()) {
    double v;
    if (getNumberParam(pnh, key, &v)) params[key] = v;
  }

  // The URDF is read even when every geometry value is a parameter: it names the joints.
  const std::string param_name = pnh.param<std::string>("robot_description_param",
                                                        "robot_description");
  UrdfGeometry urdf;
  bool have_urdf = false;
  std::string key, xml;
  if (nh.searchParam(param_name, key) && nh.getParam(key, xml)) {
    ROS_INFO_STREAM("geometry: reading " << key);
    ModelNames names;
    try {
      names = findModelNames(xml, setup.joints, setup.base_frame);
    } catch (const AckermannError& e) {
      // Geometry given in full as parameters needs no URDF: the names are taken as given.
      if (params.size() < geometryKeys().size()) throw;
      ROS_WARN_STREAM("names: " << key << ": " << e.what() << "; joint names and ~base_frame as given");
      names.joints = setup.joints;
      names.base_link = setup.base_frame;
    }
    for (const std::string& f : names.found) ROS_INFO_STREAM("names: " << key << ": " << f);
    for (const std::string& w : names.warnings) ROS_WARN_STREAM("names: " << key << ": " << w);
    setup.joints = names.joints;
    setup.base_frame = names.base_link;
    setup.prefix = names.prefix;
    if (params.size() < geometryKeys().size()) {
      // Mesh URIs resolve as in the simulator (tianracer_assets): package:// through rospack,
      // model:// through GAZEBO_MODEL_PATH, relative paths against the model file's folder.
      tianracer_assets::UriResolver resolver;
      resolver.find_package = [](const std::string& pkg) { return ros::package::getPath(pkg); };
      resolver.base_dir = pnh.param<std::string>("model_dir", "");
      urdf = geometryFromUrdf(xml, setup.joints, setup.base_frame,
                              [&](const std::string& uri) { return resolver.resolve(uri); });
      have_urdf = true;
    }
  } else {
    ROS_WARN_STREAM("geometry: no " << param_name << " parameter found from "
                                    << nh.getNamespace()
                                    << "; joint names and geometry from parameters and defaults only");
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
  setup.geometry = g;
  return setup;
}

}  // namespace tianracer_control
