#include "tianracer_sim/sensors/sensor_registry.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <sstream>

#include <urdf_model/model.h>

#include "tianracer_sim/common/text.h"

namespace tianracer_sim {
namespace {

std::string fmt(double v) { return formatShort(v); }

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

}  // namespace

// The kinds, each defined in its folder (sensors/<kind>/sim_<kind>.cpp).
const SensorKind& lidarKind();
const SensorKind& rangeKind();
const SensorKind& blockLaserKind();
const SensorKind& cameraKind();
const SensorKind& multiCameraKind();
const SensorKind& depthCameraKind();
const SensorKind& imuKind();
const SensorKind& imuPluginKind();
const SensorKind& p3dKind();
const SensorKind& bumperKind();
const SensorKind& driveKind();
const SensorKind& hectorImuKind();
const SensorKind& hectorGpsKind();
const SensorKind& hectorMagneticKind();
const SensorKind& hectorSonarKind();

const std::vector<SensorKind>& sensorKinds() {
  // To add a sensor kind: its folder sensors/<kind>/, its declaration above and one line here
  // (the order is the order in which findSensorKind tries them), its publisher in
  // ros/sensors/sensor_publishers.cpp.
  static const std::vector<SensorKind> kinds = {
      lidarKind(),  rangeKind(),       blockLaserKind(),   // sensors/ray/
      cameraKind(), multiCameraKind(), depthCameraKind(),  // sensors/camera/
      imuKind(),    imuPluginKind(),                       // sensors/imu/
      p3dKind(),    bumperKind(),      driveKind(),        // sensors/p3d/, bumper/, drives/
      hectorImuKind(), hectorGpsKind(), hectorMagneticKind(), hectorSonarKind(),  // hector/
  };
  return kinds;
}

const SensorKind* findSensorKind(const SensorSpec& sensor) {
  const SensorKind* by_type = nullptr;
  if (sensor.type.empty()) {
    for (const SensorKind& kind : sensorKinds()) {
      if (!kind.sensor_types.empty() || sensor.plugins.size() != 1) continue;
      if (contains(kind.plugins, baseName(sensor.plugins.front().filename))) return &kind;
    }
    return nullptr;
  }
  for (const SensorKind& kind : sensorKinds()) {
    if (!contains(kind.sensor_types, sensor.type)) continue;
    for (const PluginSpec& p : sensor.plugins) {
      if (contains(kind.plugins, baseName(p.filename))) return &kind;
    }
    if (!by_type) by_type = &kind;
  }
  return by_type;
}

std::vector<SensorTopic> sensorTopics(const SensorSpec& sensor, const std::string& model_name,
                                      const WarningSink& warn) {
  const SensorKind* kind = findSensorKind(sensor);
  return kind ? kind->topics(sensor, model_name, warn) : std::vector<SensorTopic>{};
}

SensorSpec modelPluginSensor(const PluginSpec& plugin) {
  SensorSpec s;
  s.name = plugin.name;
  const auto body = plugin.params.find("bodyName");
  if (body != plugin.params.end()) {
    s.link = body->second;
    s.link.erase(0, s.link.find_first_not_of(" \t\r\n"));
    s.link.erase(s.link.find_last_not_of(" \t\r\n") + 1);
  }
  s.plugins.push_back(plugin);
  s.source = plugin.source;
  s.line = plugin.line;
  return s;
}

std::string describeRobotModel(const RobotModel& model) {
  std::ostringstream out;
  const urdf::ModelInterface& urdf = *model.urdf;
  double total_mass = 0.0;
  for (const auto& [name, link] : urdf.links_) {
    if (link->inertial) total_mass += link->inertial->mass;
  }
  out << "robot '" << urdf.getName() << "' from " << model.source << ": " << urdf.links_.size()
      << " links, " << urdf.joints_.size() << " joints, total mass " << fmt(total_mass)
      << " kg\n\nlink/joint tree (mass; joint type, axis, limits):\n";

  std::function<void(const urdf::LinkConstSharedPtr&, const std::string&)> walk =
      [&](const urdf::LinkConstSharedPtr& link, const std::string& indent) {
        out << indent << link->name;
        if (link->inertial) {
          out << "  [" << fmt(link->inertial->mass) << " kg]";
        } else {
          out << "  [massless]";
        }
        out << "\n";
        for (const urdf::JointSharedPtr& joint : link->child_joints) {
          static const char* kTypes[] = {"unknown", "revolute", "continuous", "prismatic",
                                         "floating", "planar", "fixed"};
          out << indent << "  +- " << joint->name << " (" << kTypes[joint->type];
          if (joint->type != urdf::Joint::FIXED) {
            out << ", axis " << fmt(joint->axis.x) << " " << fmt(joint->axis.y) << " "
                << fmt(joint->axis.z);
          }
          if (joint->limits && (joint->type == urdf::Joint::REVOLUTE ||
                                joint->type == urdf::Joint::PRISMATIC)) {
            out << ", limits [" << fmt(joint->limits->lower) << ", " << fmt(joint->limits->upper)
                << "]";
          }
          if (joint->limits && joint->type != urdf::Joint::FIXED) {
            out << ", effort " << fmt(joint->limits->effort) << ", velocity "
                << fmt(joint->limits->velocity);
          }
          out << ")\n";
          walk(urdf.getLink(joint->child_link_name), indent + "  |  ");
        }
      };
  walk(urdf.getRoot(), "  ");

  out << "\ntransmissions:\n";
  if (model.ext.transmissions.empty()) out << "  (none)\n";
  for (const TransmissionSpec& t : model.ext.transmissions) {
    out << "  " << t.name << ": " << t.type << ", joint " << t.joint << " [";
    for (size_t i = 0; i < t.joint_interfaces.size(); ++i) {
      out << (i ? ", " : "") << toString(t.joint_interfaces[i]);
    }
    out << "], actuator " << t.actuator << ", reduction " << fmt(t.mechanical_reduction) << "\n";
  }

  // What the simulator publishes for a sensor, or why it leaves it out.
  const auto printTopics = [&](const SensorSpec& s) {
    if (!s.error.empty()) {
      out << "    left out: " << s.error << "\n";
      return;
    }
    const SensorKind* kind = findSensorKind(s);
    if (!kind) {
      out << "    left out: sensor type '" << s.type << "' is not simulated\n";
      return;
    }
    try {
      const std::vector<SensorTopic> topics = kind->topics(s, urdf.getName(), {});
      if (topics.empty()) out << "    (no gazebo_ros plugin: nothing published)\n";
      for (const SensorTopic& t : topics) {
        out << "    " << t.topic << "  " << t.msg_type << " @ " << fmt(t.rate) << " Hz\n";
      }
    } catch (const std::exception& e) {
      out << "    left out: " << e.what() << "\n";
    }
  };
  out << "\nmodel plugins:\n";
  if (model.ext.model_plugins.empty()) out << "  (none)\n";
  for (const PluginSpec& p : model.ext.model_plugins) {
    out << "  " << p.name << " (" << p.filename << ")\n";
    const SensorSpec as_sensor = modelPluginSensor(p);
    if (findSensorKind(as_sensor)) printTopics(as_sensor);
  }
  if (model.ext.ros_control) {
    out << "  ros_control: namespace " << model.ext.ros_control->robot_namespace << ", robotParam "
        << model.ext.ros_control->robot_param << "\n";
  }
  if (const auto& jsp = model.ext.joint_state_publisher) {
    out << "  joint_state_publisher: "
        << resolveTopic(jsp->robot_namespace, "joint_states") << " at "
        << fmt(jsp->update_rate) << " Hz, joints:";
    for (const std::string& j : jsp->joint_names) out << " " << j;
    out << "\n";
  }

  out << "\nsensors:\n";
  bool any = false;
  for (const auto& [link, ext] : model.ext.links) {
    for (const SensorSpec& s : ext.sensors) {
      any = true;
      out << "  " << s.name << " (" << s.type << ") on link " << link << ", "
          << fmt(s.update_rate) << " Hz\n";
      printTopics(s);
    }
  }
  if (!any) out << "  (none)\n";
  return out.str();
}

}  // namespace tianracer_sim
