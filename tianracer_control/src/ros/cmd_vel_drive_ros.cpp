// The ROS side of diff_drive_controller/DiffDriveController and
// ackermann_steering_controller/AckermannSteeringController (ros_controllers noetic-devel,
// diff_drive_controller/src/diff_drive_controller.cpp and
// ackermann_steering_controller/src/ackermann_steering_controller.cpp: init(), cmdVelCallback(),
// setOdomPubFields(), update()'s publications):
//   <controller>/cmd_vel      geometry_msgs/Twist, queue 1: linear.x and angular.z;
//   <controller>/odom         nav_msgs/Odometry, odom_frame_id -> base_frame_id, at publish_rate;
//   /tf                       tf2_msgs/TFMessage odom_frame_id -> base_frame_id (enable_odom_tf);
//   <controller>/cmd_vel_out  geometry_msgs/TwistStamped, the limited command (diff drive's
//                             publish_cmd);
//   <controller>/wheel_joint_controller_state  control_msgs/JointTrajectoryControllerState
//                             every update (diff drive's publish_wheel_joint_controller_state;
//                             publishWheelData());
//   <controller>/set_parameters, ...  the diff drive's dynamic_reconfigure
//                             (cfg/DiffDriveController.cfg; reconfCallback: taken at the next
//                             update, as upstream's realtime buffer).
#include <cmath>
#include <mutex>
#include <optional>
#include <sstream>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/TwistStamped.h>
#include <ros/console.h>
#include <ros/publisher.h>
#include <ros/subscriber.h>

#include "tianracer_control/controllers/ackermann_steering_controller.h"
#include "tianracer_control/DiffDriveControllerConfig.h"
#include "tianracer_control/controllers/diff_drive_controller.h"
#include "tianracer_control/ros/controller_ros.h"
#include "tianracer_control/ros/odom_tf_publisher.h"

namespace tianracer_control {

namespace {

class CmdVelDriveRos : public ControllerRosSide {
 public:
  static std::unique_ptr<ControllerRosSide> create(RosSideContext& context) {
    return std::make_unique<CmdVelDriveRos>(context);
  }

  explicit CmdVelDriveRos(RosSideContext& context)
      : controller_(dynamic_cast<CmdVelDriveController&>(context.controller)),
        set_(context.set),
        odom_(controller_.common().odom_frame_id, controller_.common()) {
    const CmdVelDriveController::Common& p = controller_.common();
    std::ostringstream geometry;
    if (auto* dd = dynamic_cast<const DiffDriveController*>(&controller_)) {
      geometry << "wheel separation " << dd->wheelSeparation() << ", left wheel radius "
               << dd->leftWheelRadius() << ", right wheel radius " << dd->rightWheelRadius();
    } else if (auto* ack = dynamic_cast<const AckermannSteeringController*>(&controller_)) {
      geometry << "wheel separation h " << ack->params().wheel_separation_h << ", wheel radius "
               << ack->params().wheel_radius;
    }
    ROS_INFO_STREAM_NAMED(controller_.name(), "controller '" << controller_.name()
                          << "': odometry params: " << geometry.str() << "; odom at "
                          << p.publish_rate << " Hz, " << p.odom_frame_id << " -> "
                          << p.base_frame_id << (p.enable_odom_tf ? " on /tf" : ""));
    ros::NodeHandle& nh = context.controller_nh;
    if (p.publish_cmd) cmd_vel_out_ = nh.advertise<geometry_msgs::TwistStamped>("cmd_vel_out", 100);
    odom_.advertise(nh, context.root_nh);
    sub_ = nh.subscribe<geometry_msgs::Twist>(
        "cmd_vel", 1, [this](const geometry_msgs::Twist::ConstPtr& msg) { onCmdVel(*msg); });
    if (auto* dd = dynamic_cast<DiffDriveController*>(&controller_)) {
      startReconfigure(*dd, nh);
      if (dd->params().publish_wheel_joint_controller_state) {
        wheel_state_pub_ =
            nh.advertise<control_msgs::JointTrajectoryControllerState>("wheel_joint_controller_state", 100);
        wheel_state_.joint_names = dd->wheelJointNames();
      }
    }
  }

  void apply() override {
    std::optional<geometry_msgs::Twist> cmd;
    std::optional<DiffDriveController::DynamicParams> reconfigured;
    bool brake = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      cmd.swap(pending_);
      reconfigured.swap(reconfigured_);
      std::swap(brake, brake_);
    }
    if (reconfigured) dynamic_cast<DiffDriveController&>(controller_).setDynamicParams(*reconfigured);
    if (brake) controller_.brake();
    if (!cmd) return;
    if (!set_.isRunning(controller_)) {
      ROS_ERROR_NAMED(controller_.name(), "Can't accept new commands. Controller is not running.");
      return;
    }
    controller_.setCommand(cmd->linear.x, cmd->angular.z);
  }

  void publish(double) override {
    for (const CmdVelDriveController::OdomSample& s : controller_.takeOdom()) {
      odom_.publishOdom(s.t, s.x, s.y, s.heading, s.linear, 0.0, s.angular);
      if (s.tf) odom_.publishTf(s.t, s.x, s.y, s.heading);
    }
    for (const CmdVelDriveController::CmdSample& s : controller_.takeCmdOut()) {
      if (!cmd_vel_out_) continue;
      geometry_msgs::TwistStamped msg;
      msg.header.stamp = ros::Time(s.t);
      msg.twist.linear.x = s.linear;
      msg.twist.angular.z = s.angular;
      cmd_vel_out_.publish(msg);
    }
    if (auto* dd = dynamic_cast<DiffDriveController*>(&controller_)) {
      for (DiffDriveController::WheelState& s : dd->takeWheelStates()) {
        if (!wheel_state_pub_) continue;
        wheel_state_.header.stamp = ros::Time(s.t);
        const auto fill = [](trajectory_msgs::JointTrajectoryPoint* p, DiffDriveController::WheelState::Point& q) {
          p->positions.swap(q.positions);
          p->velocities.swap(q.velocities);
          p->accelerations.swap(q.accelerations);
          p->effort.swap(q.effort);
        };
        fill(&wheel_state_.desired, s.desired);
        fill(&wheel_state_.actual, s.actual);
        fill(&wheel_state_.error, s.error);
        wheel_state_pub_.publish(wheel_state_);
      }
    }
  }

  void clear() override {
    std::lock_guard<std::mutex> lock(mutex_);
    pending_.reset();
    brake_ = false;
  }
  std::vector<std::string> commandTopics() const override { return {sub_.getTopic()}; }

 private:
  using Config = tianracer_control::DiffDriveControllerConfig;

  // init()'s dynamic_reconfigure server, starting from the controller's values.
  void startReconfigure(const DiffDriveController& dd, ros::NodeHandle& nh) {
    const DiffDriveController::DynamicParams d = dd.dynamicParams();
    Config config;
    config.left_wheel_radius_multiplier = d.left_wheel_radius_multiplier;
    config.right_wheel_radius_multiplier = d.right_wheel_radius_multiplier;
    config.wheel_separation_multiplier = d.wheel_separation_multiplier;
    config.publish_rate = d.publish_rate;
    config.enable_odom_tf = d.enable_odom_tf;
    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<Config>>(reconfigure_mutex_, nh);
    {
      boost::recursive_mutex::scoped_lock lock(reconfigure_mutex_);
      reconfigure_->updateConfig(config);
    }
    reconfigure_->setCallback([this](Config& c, uint32_t) {
      DiffDriveController::DynamicParams p;
      p.left_wheel_radius_multiplier = c.left_wheel_radius_multiplier;
      p.right_wheel_radius_multiplier = c.right_wheel_radius_multiplier;
      p.wheel_separation_multiplier = c.wheel_separation_multiplier;
      p.publish_rate = c.publish_rate;
      p.enable_odom_tf = c.enable_odom_tf;
      ROS_INFO_STREAM_NAMED(controller_.name(), "controller '" << controller_.name()
                            << "': Dynamic Reconfigure: left wheel radius multiplier "
                            << p.left_wheel_radius_multiplier << ", right wheel radius multiplier "
                            << p.right_wheel_radius_multiplier << ", wheel separation multiplier "
                            << p.wheel_separation_multiplier << ", publish rate " << p.publish_rate
                            << ", enable odom tf " << p.enable_odom_tf);
      std::lock_guard<std::mutex> lock(mutex_);
      reconfigured_ = p;
    });
  }

  // cmdVelCallback(): runs on a spinner thread; the controller is the sim loop's.
  void onCmdVel(const geometry_msgs::Twist& cmd) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!controller_.common().allow_multiple_cmd_vel_publishers && sub_.getNumPublishers() > 1) {
      ROS_ERROR_STREAM_THROTTLE_NAMED(1.0, controller_.name(),
                                      "Detected " << sub_.getNumPublishers()
                                                  << " publishers. Only 1 publisher is allowed. "
                                                     "Going to brake.");
      brake_ = true;
      return;
    }
    if (!std::isfinite(cmd.angular.z) || !std::isfinite(cmd.linear.x)) {
      nan_.warn("controller '" + controller_.name() +
                "': Received NaN in velocity command. Ignoring.");
      return;
    }
    pending_ = cmd;
  }

  CmdVelDriveController& controller_;
  const ControllerSet& set_;
  ros::Subscriber sub_;
  ros::Publisher cmd_vel_out_, wheel_state_pub_;
  control_msgs::JointTrajectoryControllerState wheel_state_;
  OdomTfPublisher odom_;
  std::mutex mutex_;
  std::optional<geometry_msgs::Twist> pending_;
  std::optional<DiffDriveController::DynamicParams> reconfigured_;
  bool brake_ = false;
  ThrottledWarning nan_;
  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<Config>> reconfigure_;  // last: goes first
};

TIANRACER_CONTROLLER_ROS_SIDE(DiffDriveController::kType, CmdVelDriveRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(AckermannSteeringController::kType, CmdVelDriveRos::create);

}  // namespace

}  // namespace tianracer_control
