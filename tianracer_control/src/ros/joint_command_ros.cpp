// The ROS sides of the Joint and JointGroup controllers: <controller>/command, std_msgs/Float64
// for one joint (forward_command_controller.h, effort_controllers' and velocity_controllers'
// JointPositionController / JointVelocityController), std_msgs/Float64MultiArray for a group
// (forward_joint_group_command_controller.h, effort_controllers/JointGroupPositionController).
#include <cmath>
#include <mutex>
#include <optional>
#include <sstream>

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
  explicit Float64CommandRos(RosSideContext& context) : controller_(context.controller) {
    sub_ = context.controller_nh.subscribe<std_msgs::Float64>(
        "command", 10, [this](const std_msgs::Float64::ConstPtr& msg) { onCommand(msg->data); });
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
  ros::Subscriber sub_;
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
