// The ROS sides of the Joint and JointGroup controllers: <controller>/command, std_msgs/Float64
// for one joint (forward_command_controller.h, effort_controllers' and velocity_controllers'
// JointPositionController / JointVelocityController), std_msgs/Float64MultiArray for a group
// (forward_joint_group_command_controller.h, effort_controllers/JointGroupPositionController).
// The PID ones also publish <controller>/state, control_msgs/JointControllerState, every 10th
// update (controllers/pid_state.h), stamped with the update's sim time.
#include <cmath>
#include <mutex>
#include <optional>
#include <sstream>

#include <control_msgs/JointControllerState.h>
#include <ros/console.h>
#include <ros/subscriber.h>
#include <std_msgs/Float64.h>
#include <std_msgs/Float64MultiArray.h>

#include "tianracer_control/controllers/effort_joint_position_controller.h"
#include "tianracer_control/controllers/effort_joint_velocity_controller.h"
#include "tianracer_control/controllers/forward_command_controller.h"
#include "tianracer_control/controllers/joint_group_controller.h"
#include "tianracer_control/ros/controller_ros.h"

namespace tianracer_control {

namespace {

class Float64CommandRos : public ControllerRosSide {
 public:
  static std::unique_ptr<ControllerRosSide> create(RosSideContext& context) {
    return std::make_unique<Float64CommandRos>(context);
  }
  explicit Float64CommandRos(RosSideContext& context)
      : controller_(context.controller),
        pid_state_(dynamic_cast<const PidStateSource*>(&context.controller)) {
    sub_ = context.controller_nh.subscribe<std_msgs::Float64>(
        "command", 10, [this](const std_msgs::Float64::ConstPtr& msg) { onCommand(msg->data); });
    // A RealtimePublisher of queue 1 upstream.
    if (pid_state_) state_pub_ = context.controller_nh.advertise<control_msgs::JointControllerState>("state", 1);
  }
  void publish(double t) override {
    if (!pid_state_ || pid_state_->pidState().seq == published_seq_) return;
    const PidStateSample& s = pid_state_->pidState();
    published_seq_ = s.seq;
    control_msgs::JointControllerState msg;
    msg.header.stamp = ros::Time(t);
    msg.set_point = s.set_point;
    msg.process_value = s.process_value;
    msg.process_value_dot = s.process_value_dot;
    msg.error = s.error;
    msg.time_step = s.time_step;
    msg.command = s.command;
    msg.p = s.gains.p;
    msg.i = s.gains.i;
    msg.d = s.gains.d;
    msg.i_clamp = s.gains.i_clamp_max;
    msg.antiwindup = s.gains.antiwindup;
    state_pub_.publish(msg);
  }
  void apply() override {
    std::optional<double> pending;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending.swap(pending_);
    }
    if (pending) controller_.setCommand(*pending);
  }
  void clear() override {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.reset();
  }
  std::vector<std::string> commandTopics() const override { return {sub_.getTopic()}; }

 private:
  void onCommand(double value) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!std::isfinite(value)) {
      std::ostringstream text;
      text << "controller '" << controller_.name() << "': ignoring command " << value
           << " (not finite)";
      ignored_.warn(text.str());
      return;
    }
    pending_ = value;
  }

  Controller& controller_;
  const PidStateSource* pid_state_;  // null: not a PID controller, no `state`
  ros::Subscriber sub_;
  ros::Publisher state_pub_;
  std::uint64_t published_seq_ = 0;
  std::mutex mutex_;
  std::optional<double> pending_;
  ThrottledWarning ignored_;
};

TIANRACER_CONTROLLER_ROS_SIDE(EffortJointPositionController::kType, Float64CommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(EffortJointVelocityController::kType, Float64CommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(ForwardCommandController::kEffortType, Float64CommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(ForwardCommandController::kVelocityType, Float64CommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(ForwardCommandController::kPositionType, Float64CommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(VelocityJointPositionController::kType, Float64CommandRos::create);

class JointGroupCommandRos : public ControllerRosSide {
 public:
  static std::unique_ptr<ControllerRosSide> create(RosSideContext& context) {
    return std::make_unique<JointGroupCommandRos>(context);
  }
  explicit JointGroupCommandRos(RosSideContext& context)
      : controller_(dynamic_cast<JointGroupController&>(context.controller)) {
    sub_ = context.controller_nh.subscribe<std_msgs::Float64MultiArray>(
        "command", 1, [this](const std_msgs::Float64MultiArray::ConstPtr& msg) { onCommand(*msg); });
  }
  void apply() override {
    std::optional<std::vector<double>> pending;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending.swap(pending_);
    }
    if (!pending) return;
    // Checked again here (the size was checked on arrival); a refusal is logged as upstream.
    const std::string error = controller_.setCommands(*pending);
    if (!error.empty()) ROS_ERROR_STREAM("controller '" << controller_.name() << "': " << error);
  }
  void clear() override {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.reset();
  }
  std::vector<std::string> commandTopics() const override { return {sub_.getTopic()}; }

 private:
  void onCommand(const std_msgs::Float64MultiArray& msg) {
    // commandCB: a command of the wrong size is refused with upstream's message.
    if (msg.data.size() != controller_.joints().size()) {
      ROS_ERROR_STREAM("Dimension of command (" << msg.data.size()
                                                << ") does not match number of joints ("
                                                << controller_.joints().size()
                                                << ")! Not executing!");
      return;
    }
    for (double v : msg.data) {
      if (std::isfinite(v)) continue;
      std::ostringstream text;
      text << "controller '" << controller_.name() << "': ignoring command with value " << v
           << " (not finite)";
      std::lock_guard<std::mutex> lock(mutex_);
      ignored_.warn(text.str());
      return;
    }
    std::lock_guard<std::mutex> lock(mutex_);
    pending_ = msg.data;
  }

  JointGroupController& controller_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::optional<std::vector<double>> pending_;
  ThrottledWarning ignored_;
};

TIANRACER_CONTROLLER_ROS_SIDE(JointGroupController::kEffortType, JointGroupCommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(JointGroupController::kVelocityType, JointGroupCommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(JointGroupController::kPositionType, JointGroupCommandRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(JointGroupController::kEffortPositionType,
                              JointGroupCommandRos::create);

}  // namespace

}  // namespace tianracer_control
