// The ROS side of one robot of the Simulator: its controllers' command topics, its joint
// states (the joint_state_publisher plugin's and joint_state_controller's streams, merged where
// they share a topic), its ground truth (<ns>/ground_truth/odom), the world -> odom TF at its
// spawn pose, and the sensor topics it claimed.
#ifndef TIANRACER_SIM_ROS_ROBOT_BRIDGE_H
#define TIANRACER_SIM_ROS_ROBOT_BRIDGE_H

#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <tianracer_control/ros/controller_adapter.h>

#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

class RobotBridge {
 public:
  struct Options {
    std::string ns;           // ros_control namespace, e.g. "/tianracer"
    std::string tf_prefix;    // "" for a robot alone; e.g. "tianracer_02"
    std::string odom_frame;   // "" = no world -> odom TF
    double ground_truth_rate = 50.0;
  };

  /// Advertises and subscribes on `root` (the node's callback queue). Throws ModelError for a
  /// joint_states joint that is not a movable joint.
  RobotBridge(Simulator& sim, ModelId id, Options options, ros::NodeHandle root,
              tf2_ros::StaticTransformBroadcaster& static_tf);

  ModelId id() const { return id_; }
  RobotId physicsId() const { return physics_id_; }
  const std::string& ns() const { return options_.ns; }
  const std::string& tfPrefix() const { return options_.tf_prefix; }
  /// Commands received since the last call go to the controllers (before each step).
  void applyCommands() { commands_->apply(); }
  /// Drops commands not yet applied (reset_simulation).
  void clearCommands() { commands_->clear(); }
  std::vector<std::string> commandTopics() const { return commands_->topics(); }
  /// joint_states and ground truth due at sim time t.
  void publish(double t);
  /// Time went back: the schedules restart at t.
  void restart(double t);
  /// Sensor topics the robot's sensors publish on.
  std::vector<std::string>& topics() { return topics_; }

 private:
  struct JointStateStream {
    ros::Publisher pub;
    std::vector<int> joints;  // PhysicsRobot joint indices
    Schedule schedule;
    sensor_msgs::JointState msg;
  };
  void setUpJointStates(ros::NodeHandle& root);

  Simulator& sim_;
  ModelId id_;
  RobotId physics_id_;
  Options options_;
  std::string base_frame_;  // tf_prefix + root link
  std::shared_ptr<tianracer_control::ControllerCommandSubscribers> commands_;
  std::vector<JointStateStream> joint_states_;
  ros::Publisher ground_truth_;
  Schedule ground_truth_schedule_;
  std::vector<std::string> topics_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_ROBOT_BRIDGE_H
