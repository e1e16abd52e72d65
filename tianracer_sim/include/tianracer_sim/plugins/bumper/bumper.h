// Gazebo's contact sensor with the libgazebo_ros_bumper plugin: the contacts of the sensor's
// link, grouped by touching pair, as gazebo_msgs/ContactsState reports them. ROS-free.
//
// Per pair (own collision, other collision), every contact point p with normal n (unit, pushing
// the sensor's link out), depth d and normal impulse J over the step dt gives the force on the
// sensor's link f = (J / dt) n, no torque. With frameName "world" they are in the world frame;
// with frameName a link F of the robot: p_F = R_WF^T (p_W - p_WF), n_F = R_WF^T n_W,
// f_F = R_WF^T f_W (as gazebo_ros_bumper).
#ifndef TIANRACER_SIM_PLUGINS_BUMPER_BUMPER_H
#define TIANRACER_SIM_PLUGINS_BUMPER_BUMPER_H

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/sensor_topics.h"
#include "tianracer_sim/plugins/link_data.h"  // LinkContact

namespace tianracer_sim {

struct BumperConfig {
  std::string name;                       // the sensor's name
  std::string link;                       // the sensor's link
  std::string robot_namespace;            // "" unless given
  std::string topic_name = "bumper_states";
  std::string frame_name = "world";       // "world" or a link of the robot
  double update_rate = 0.0;               // the sensor's <update_rate>; 0 = every step
  std::string topic() const { return resolveTopic(robot_namespace, topic_name); }
};

/// A <sensor type="contact"> with its libgazebo_ros_bumper plugin (bumperTopicName, frameName,
/// robotNamespace). Without the plugin Gazebo publishes nothing (topic_name ""). Throws
/// SensorError naming the model, sensor and value.
BumperConfig parseBumperConfig(const SensorSpec& sensor, const std::string& model_name,
                               const WarningSink& warn = {});
/// gazebo_msgs/ContactsState on topic() at update_rate (nothing without the plugin).
std::vector<SensorTopic> publishedTopics(const BumperConfig& config);

/// One contact point of the sensor's link with something else (own: "model::link").
using BumperContact = LinkContact;

/// One touching pair, in the output frame.
struct BumperState {
  std::string collision1, collision2;
  std::vector<Eigen::Vector3d> positions, normals, forces;
  std::vector<double> depths;
  Eigen::Vector3d total_force = Eigen::Vector3d::Zero();
};

/// Groups `contacts` by pair (in order of first appearance) and expresses them in frame F;
/// `out` is cleared first. dt > 0.
void bumperStates(const std::vector<BumperContact>& contacts, const Eigen::Isometry3d& X_WF,
                  double dt, std::vector<BumperState>* out);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_BUMPER_BUMPER_H
