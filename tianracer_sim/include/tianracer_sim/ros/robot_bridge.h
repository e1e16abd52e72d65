// The ROS side of one robot of the Simulator: its controllers' command topics, its joint
// states (the joint_state_publisher plugin's and running joint_state_controllers' streams,
// merged where they share a topic), its ground truth (<ns>/ground_truth/odom), the world ->
// odom TF at its spawn pose, the sensor topics it claimed, and, with gazebo_ros_control,
// controller_manager's services (controller_manager_bridge.h), after which the command topics
// and joint states follow the controllers loaded and running.
#ifndef TIANRACER_SIM_ROS_ROBOT_BRIDGE_H
#define TIANRACER_SIM_ROS_ROBOT_BRIDGE_H

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <tianracer_control/ros/controller_adapter.h>
#include <atomic>

#include "tianracer_sim/ros/controller_manager_bridge.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

class RobotBridge {
 public:
  /// Its step-profile rows, in the order it fills them (the node registers them up front so
  /// that the table follows the loop).
  static constexpr const char* kProfileRows[] = {
      "ros: joint_states", "ros: joint_states / convert",
      "ros: joint_states / serialise and send", "ros: ground truth odom",
      "ros: ground truth odom / convert", "ros: ground truth odom / serialise and send"};

  struct Options {
    std::string ns;           // ros_control namespace, e.g. "/tianracer"
    std::string tf_prefix;    // "" for a robot alone; e.g. "tianracer_02"
    std::string odom_frame;   // "" = no world -> odom TF
    double ground_truth_rate = 50.0;
    /// Serve <ns>/controller_manager/ (a model with gazebo_ros_control), loading controllers'
    /// parameters from control_ns/<name>.
    bool controller_manager = false;
    std::string control_ns;
    /// gazebo_ros_control's <eStopTopic> (std_msgs/Bool under ns); "" = none.
    std::string e_stop_topic;
    /// After a controller_manager call changed the controllers (the node's lockstep follows).
    std::function<void()> controllers_changed;
  };

  /// Advertises and subscribes on `root` (the node's callback queue). Throws ModelError for a
  /// joint_states joint that is not a movable joint.
  RobotBridge(Simulator& sim, ModelId id, Options options, ros::NodeHandle root,
              tf2_ros::StaticTransformBroadcaster& static_tf);

  ModelId id() const { return id_; }
  RobotId physicsId() const { return physics_id_; }
  const std::string& ns() const { return options_.ns; }
  const std::string& tfPrefix() const { return options_.tf_prefix; }
  /// Commands received since the last call go to the controllers, the e-stop's state to the
  /// hardware (before each step).
  void applyCommands();
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
    /// Per joint: the robot's handle whose state is published, or -1 (the physics joint's).
    /// Handles where the hardware makes the state (SteerBotHardwareGazebo), as upstream's
    /// joint_state_controller reads its JointStateInterface.
    std::vector<int> handles;
    Schedule schedule;
    sensor_msgs::JointState msg;
  };
  /// The joint state streams of the plugin and of the running joint_state_controllers.
  std::vector<JointStateStream> makeJointStates();
  /// After a load, unload or switch: command topics and joint_states follow the controllers.
  void controllersChanged();

  Simulator& sim_;
  ModelId id_;
  RobotId physics_id_;
  Options options_;
  ros::NodeHandle root_;
  std::string base_frame_;  // tf_prefix + root link
  std::shared_ptr<tianracer_control::ControllerCommandSubscribers> commands_;
  std::vector<JointStateStream> joint_states_;
  ros::Publisher ground_truth_;
  nav_msgs::Odometry ground_truth_msg_;  // filled in place at each publication
  Schedule ground_truth_schedule_;
  std::vector<std::string> topics_;
  ros::Subscriber e_stop_sub_;
  std::shared_ptr<std::atomic<bool>> e_stop_;  // the last <eStopTopic> message's data
  // The step profile's rows (sim_.profile(); -1 when not profiling).
  struct {
    int joint_states = -1, joint_states_convert = -1, joint_states_send = -1;
    int ground_truth = -1, ground_truth_convert = -1, ground_truth_send = -1;
  } rows_;
  // Last: its services go first (they call into the members above).
  std::unique_ptr<ControllerManagerBridge> controller_manager_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_ROBOT_BRIDGE_H
