#include "tianracer_sim/model/sensor_topics.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>

namespace tianracer_sim {
namespace {

std::string param(const PluginSpec& plugin, const std::string& key, const std::string& fallback) {
  const auto it = plugin.params.find(key);
  return it == plugin.params.end() || it->second.empty() ? fallback : it->second;
}

double rateParam(const PluginSpec& plugin, const std::string& key, double sensor_rate) {
  const auto it = plugin.params.find(key);
  if (it == plugin.params.end()) return sensor_rate;
  char* end = nullptr;
  const double rate = std::strtod(it->second.c_str(), &end);
  // gazebo_ros: updateRate 0 (or absent) means "as fast as the sensor".
  return (end == it->second.c_str() || !std::isfinite(rate) || rate <= 0.0) ? sensor_rate : rate;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string fmt(double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%g", v);
  return buf;
}

}  // namespace

std::string resolveTopic(const std::string& ns, const std::string& name) {
  std::string joined = (!name.empty() && name[0] == '/') ? name : "/" + ns + "/" + name;
  std::string out;
  for (char c : joined) {
    if (c == '/' && !out.empty() && out.back() == '/') continue;
    out.push_back(c);
  }
  if (out.size() > 1 && out.back() == '/') out.pop_back();
  return out;
}

std::vector<SensorTopic> sensorTopics(const SensorSpec& sensor) {
  std::vector<SensorTopic> topics;
  for (const PluginSpec& plugin : sensor.plugins) {
    const std::string ns = param(plugin, "robotNamespace", "");
    if (endsWith(plugin.filename, "libgazebo_ros_laser.so") ||
        endsWith(plugin.filename, "libgazebo_ros_gpu_laser.so")) {
      topics.push_back({resolveTopic(ns, param(plugin, "topicName", "/world")),
                        "sensor_msgs/LaserScan", sensor.update_rate});
    } else if (endsWith(plugin.filename, "libgazebo_ros_camera.so")) {
      const std::string cam_ns = resolveTopic(ns, param(plugin, "cameraName", ""));
      const double rate = rateParam(plugin, "updateRate", sensor.update_rate);
      topics.push_back({resolveTopic(cam_ns, param(plugin, "imageTopicName", "image_raw")),
                        "sensor_msgs/Image", rate});
      topics.push_back({resolveTopic(cam_ns, param(plugin, "cameraInfoTopicName", "camera_info")),
                        "sensor_msgs/CameraInfo", rate});
    } else if (endsWith(plugin.filename, "libgazebo_ros_openni_kinect.so")) {
      const std::string cam_ns = resolveTopic(ns, param(plugin, "cameraName", ""));
      const double info_rate = rateParam(plugin, "updateRate", sensor.update_rate);
      topics.push_back({resolveTopic(cam_ns, param(plugin, "imageTopicName", "image_raw")),
                        "sensor_msgs/Image", sensor.update_rate});
      topics.push_back(
          {resolveTopic(cam_ns, param(plugin, "depthImageTopicName", "depth/image_raw")),
           "sensor_msgs/Image", sensor.update_rate});
      topics.push_back({resolveTopic(cam_ns, param(plugin, "pointCloudTopicName", "points")),
                        "sensor_msgs/PointCloud2", sensor.update_rate});
      topics.push_back({resolveTopic(cam_ns, param(plugin, "cameraInfoTopicName", "camera_info")),
                        "sensor_msgs/CameraInfo", info_rate});
      topics.push_back({resolveTopic(cam_ns, param(plugin, "depthImageCameraInfoTopicName",
                                                   "depth/camera_info")),
                        "sensor_msgs/CameraInfo", info_rate});
    }
  }
  return topics;
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

  out << "\nmodel plugins:\n";
  if (model.ext.model_plugins.empty()) out << "  (none)\n";
  for (const PluginSpec& p : model.ext.model_plugins) out << "  " << p.name << " (" << p.filename << ")\n";
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
      for (const SensorTopic& t : sensorTopics(s)) {
        out << "    " << t.topic << "  " << t.msg_type << " @ " << fmt(t.rate) << " Hz\n";
      }
    }
  }
  if (!any) out << "  (none)\n";
  return out.str();
}

}  // namespace tianracer_sim
