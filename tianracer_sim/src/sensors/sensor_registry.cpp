#include "tianracer_sim/sensors/sensor_registry.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <sstream>

#include <urdf_model/model.h>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/sensors/ray/ray_plugins.h"
#include "tianracer_sim/sensors/ray/ray_sensor.h"
#include "tianracer_sim/sensors/camera/camera_sensor.h"
#include "tianracer_sim/sensors/bumper/bumper.h"
#include "tianracer_sim/sensors/drives/drives.h"
#include "tianracer_sim/sensors/imu/imu_sensor.h"
#include "tianracer_sim/sensors/camera/multicamera_topics.h"
#include "tianracer_sim/sensors/p3d/p3d.h"

namespace tianracer_sim {
namespace {

std::string fmt(double v) { return formatShort(v); }

bool contains(const std::vector<std::string>& list, const std::string& s) {
  return std::find(list.begin(), list.end(), s) != list.end();
}

std::vector<SensorTopic> lidarTopics(const SensorSpec& sensor, const std::string&, const WarningSink& warn) {
  return publishedTopics(parseRaySensorConfig(sensor, warn));
}

// libgazebo_ros_camera: <robotNamespace>/<cameraName>/{image, camera_info} at updateRate (0 =
// the sensor rate). Without a plugin Gazebo renders but publishes nothing.
std::vector<SensorTopic> cameraTopics(const SensorSpec& sensor, const std::string& model_name,
                                      const WarningSink& warn) {
  CameraConfig c = parseCameraConfig(sensor, warn);
  if (!c.has_plugin) return {};
  const std::string ns = resolveTopic(c.robot_namespace, c.camera_name);
  return {{resolveTopic(ns, c.image_topic), "sensor_msgs/Image", c.publishRate()},
          {resolveTopic(ns, c.camera_info_topic), "sensor_msgs/CameraInfo", c.publishRate()}};
}

// libgazebo_ros_openni_kinect / libgazebo_ros_depth_camera: images and cloud at the sensor
// rate, both camera_infos at the plugin's updateRate.
std::vector<SensorTopic> depthCameraTopics(const SensorSpec& sensor, const std::string& model_name,
                                           const WarningSink& warn) {
  DepthCameraConfig d = parseDepthCameraConfig(sensor, warn);
  const CameraConfig& c = d.camera;
  if (!c.has_plugin) return {};
  const std::string ns = resolveTopic(c.robot_namespace, c.camera_name);
  return {{resolveTopic(ns, c.image_topic), "sensor_msgs/Image", c.update_rate},
          {resolveTopic(ns, d.depth_image_topic), "sensor_msgs/Image", c.update_rate},
          {resolveTopic(ns, d.point_cloud_topic), "sensor_msgs/PointCloud2", c.update_rate},
          {resolveTopic(ns, c.camera_info_topic), "sensor_msgs/CameraInfo", c.publishRate()},
          {resolveTopic(ns, d.depth_camera_info_topic), "sensor_msgs/CameraInfo",
           c.publishRate()}};
}

std::vector<SensorTopic> imuTopics(const SensorSpec& sensor, const std::string& model_name,
                                   const WarningSink& warn) {
  return publishedTopics(parseImuSensorConfig(sensor, model_name, warn));
}

std::vector<SensorTopic> imuPluginTopics(const SensorSpec& sensor, const std::string& model_name,
                                         const WarningSink& warn) {
  return publishedTopics(parseImuPluginConfig(sensor, model_name, warn));
}

std::vector<SensorTopic> p3dTopics(const SensorSpec& sensor, const std::string& model_name,
                                   const WarningSink& warn) {
  return publishedTopics(parseP3dConfig(sensor, model_name, warn));
}

std::vector<SensorTopic> rangeTopics(const SensorSpec& sensor, const std::string&,
                                     const WarningSink& warn) {
  return publishedTopics(parseRangeConfig(sensor, warn));
}

std::vector<SensorTopic> blockLaserTopics(const SensorSpec& sensor, const std::string&,
                                          const WarningSink& warn) {
  return publishedTopics(parseBlockLaserConfig(sensor, warn));
}

std::vector<SensorTopic> bumperTopics(const SensorSpec& sensor, const std::string& model_name,
                                     const WarningSink& warn) {
  return publishedTopics(parseBumperConfig(sensor, model_name, warn));
}

std::vector<SensorTopic> driveTopics(const SensorSpec& sensor, const std::string& model_name,
                                     const WarningSink& warn) {
  return publishedTopics(parseDriveConfig(sensor, model_name, warn));
}

}  // namespace

const std::vector<SensorKind>& sensorKinds() {
  // To add a sensor type: one line here, its publisher in ros/sensors/sensor_publishers.cpp.
  static const std::vector<SensorKind> kinds = {
      {"lidar", {"ray", "gpu_ray"},
       {"libgazebo_ros_laser.so", "libgazebo_ros_gpu_laser.so", "libgazebo_ros_velodyne_laser.so",
        "libgazebo_ros_velodyne_gpu_laser.so"},
       &lidarTopics},
      {"range", {"ray", "gpu_ray"}, {"libgazebo_ros_range.so"}, &rangeTopics},
      {"block_laser", {"ray", "gpu_ray"}, {"libgazebo_ros_block_laser.so"}, &blockLaserTopics},
      {"camera", {"camera"}, {"libgazebo_ros_camera.so", "libgazebo_ros_triggered_camera.so"},
       &cameraTopics},
      {"multicamera", {"multicamera"}, {"libgazebo_ros_multicamera.so"}, &multiCameraTopics},
      {"depth_camera", {"depth"},
       {"libgazebo_ros_openni_kinect.so", "libgazebo_ros_depth_camera.so"}, &depthCameraTopics},
      {"imu", {"imu"}, {"libgazebo_ros_imu_sensor.so"}, &imuTopics},
      {"imu_plugin", {}, {"libgazebo_ros_imu.so"}, &imuPluginTopics},
      {"p3d", {}, {"libgazebo_ros_p3d.so"}, &p3dTopics},
      {"bumper", {"contact"}, {"libgazebo_ros_bumper.so"}, &bumperTopics},
      {"drive", {},
       {"libgazebo_ros_diff_drive.so", "libgazebo_ros_skid_steer_drive.so",
        "libgazebo_ros_planar_move.so"},
       &driveTopics},
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
