// Ground truth as Gazebo's model plugin libgazebo_ros_p3d publishes it (nav_msgs/Odometry of one
// link), and the link motion it is computed from. ROS-free.
//
// From the link's pose X_WB and world-frame velocities (v_W of its origin, w_W):
//  - frameName world (or map): position and orientation in the world, velocities in the world
//    frame (not the body frame: that is p3d's convention, unlike the sim's ground_truth/odom);
//  - frameName a link R of the model: position R_WR^T (p_WB - p_WR), orientation q_WR^-1 q_WB,
//    velocities R_WR^T (v_WB - v_WR) and R_WR^T (w_WB - w_WR). Gazebo composes the orientation
//    and rotates the velocities on the other side of R_WR (the same only when R_WR is the
//    identity); we express them in R, which is what the frame id says;
//  - then xyzOffsets added to the position, rpyOffsets applied in front of the orientation;
//  - gaussianNoise: N(0, gn) on each twist component, covariance diagonals gn^2 (pose and twist).
#ifndef TIANRACER_SIM_PLUGINS_P3D_P3D_H
#define TIANRACER_SIM_PLUGINS_P3D_P3D_H

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"
#include "tianracer_sim/plugins/link_data.h"  // LinkState

namespace tianracer_sim {

struct P3dConfig {
  std::string name;             // the plugin's name
  std::string link;             // bodyName
  std::string robot_namespace;  // "" unless given
  std::string topic_name;
  std::string frame_name = "world";
  std::string reference_link;   // frameName when it is a link ("" for world and map)
  double update_rate = 0.0;     // Hz; 0 = every step
  double gaussian_noise = 0.0;
  Eigen::Vector3d xyz_offsets = Eigen::Vector3d::Zero();
  Eigen::Vector3d rpy_offsets = Eigen::Vector3d::Zero();
  std::uint64_t seed = 0;

  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
};

/// The model plugin given as a SensorSpec of type "" (modelPluginSensor()). bodyName and
/// topicName are required (Gazebo does not load the plugin without them). Throws SensorError
/// naming the model, plugin and value.
P3dConfig parseP3dConfig(const SensorSpec& sensor, const std::string& model_name,
                         const WarningSink& warn = {});
/// nav_msgs/Odometry on topic() at update_rate.
std::vector<SensorTopic> publishedTopics(const P3dConfig& config);

/// A link's velocities from its poses at consecutive steps, where the physics gives none:
/// v = displacement / dt, w from the rotation over the step (0 at the first step).
class LinkMotion {
 public:
  void reset() { steps_ = 0; }
  const LinkState& record(double t, const Eigen::Isometry3d& X_WL);
  /// A state known exactly (pose and velocities from the physics).
  const LinkState& set(double t, const LinkState& state);
  const LinkState& state() const { return state_; }

 private:
  int steps_ = 0;
  double t_ = 0.0;
  LinkState state_;
};

struct P3dReading {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  double variance = 0.0;  // gn^2 on the pose and twist covariance diagonals
};

class P3dSensor {
 public:
  explicit P3dSensor(P3dConfig config);
  const P3dConfig& config() const { return config_; }
  /// The reading for the body's state, relative to `reference` when the frame is a link.
  const P3dReading& measure(const LinkState& body, const LinkState* reference);

 private:
  P3dConfig config_;
  Eigen::Quaterniond q_offset_;
  std::mt19937_64 rng_;
  P3dReading reading_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_P3D_P3D_H
