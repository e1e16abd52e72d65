// Gazebo multicamera sensors (<sensor type="multicamera"> with several <camera name="..">, each
// with its own <pose>) and the libgazebo_ros_multicamera plugin: parsed into one CameraConfig
// per camera, so that each renders and publishes as a camera does. ROS-free.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_MULTICAMERA_CONFIG_H
#define TIANRACER_SIM_PLUGINS_CAMERA_MULTICAMERA_CONFIG_H

#include <string>
#include <vector>

#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/camera/camera_config.h"

namespace tianracer_sim {

/// A multicamera sensor and its plugin, as gazebo_ros_multicamera reads them:
/// - every <camera> is a camera of its own: <horizontal_fov>, <image>, <clip>, <noise> as for a
///   camera sensor, and <pose> relative to the sensor (X_LS of camera i = sensor pose * pose);
/// - topics: <robotNamespace>/<cameraName><suffix>/<imageTopicName> and .../<cameraInfoTopicName>,
///   where the suffix of camera i is the i-th entry of <cameraSuffixes> (comma separated), else
///   "/left" and "/right" for a pair named *left* and *right*, else "/<camera name>";
/// - <frameName>: one frame for all cameras, or one per camera (comma separated); default the
///   sensor's link;
/// - hackBaseline: only a camera whose name contains "right" gets it, P[3] = -f * hackBaseline
///   (the left camera's P[3] is 0), the ROS stereo convention for the right camera;
/// - <updateRate> (0 = the sensor's <update_rate>) and the other libgazebo_ros_camera
///   parameters (distortion, Cx, Cy, focalLength) apply to every camera.
struct MultiCameraConfig {
  std::string name;  // <sensor name>
  std::string link;
  double update_rate = 0.0;
  bool has_plugin = false;
  std::vector<CameraConfig> cameras;  // in the order of the <camera> elements; >= 2
  /// Publish rate of every camera (the plugin's updateRate, else the sensor rate).
  double publishRate() const { return cameras.empty() ? 0.0 : cameras.front().publishRate(); }
};

/// Parses and validates a multicamera sensor of robot `model_name`. Throws CameraError naming
/// the robot, the sensor and the value: fewer than two cameras, two cameras with the same
/// name, a camera without a name, a bad <pose>, a <cameraSuffixes> or <frameName> list whose
/// length does not match the cameras, and every camera error parseCameraConfig reports.
/// Unknown elements and plugin parameters are reported once to `warn`.
MultiCameraConfig parseMultiCameraConfig(const SensorSpec& sensor, const std::string& model_name,
                                         const WarningSink& warn = {});

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_MULTICAMERA_CONFIG_H
