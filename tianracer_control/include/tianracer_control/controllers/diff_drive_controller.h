// diff_drive_controller/DiffDriveController (ros_controllers noetic-devel,
// diff_drive_controller/src/diff_drive_controller.cpp), without ROS: its own keys (wheels,
// geometry, multipliers) over what it shares with ackermann_steering_controller
// (cmd_vel_drive_controller.h), its odometry from the wheels and its wheel commands:
//   odometry: each side's mean wheel position (skid steer: several wheels a side); a NaN wheel
//     position skips the update;
//   left = (lin - ang ws / 2) / lwr, right = (lin + ang ws / 2) / rwr to every wheel of a side
//     (ws, lwr, rwr: wheel_separation and wheel_radius times their multipliers).
#ifndef TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_CONTROLLER_H

#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controllers/cmd_vel_drive_controller.h"
#include "tianracer_control/controllers/outbox.h"

namespace tianracer_control {

/// The wheel joints' names from `key` (left_wheel, right_wheel): a string or a non-empty list
/// of strings (getWheelNames). Throws ControllerError with upstream's messages.
std::vector<std::string> readWheelNames(ControllerParams& params, const std::string& key);

class DiffDriveController : public CmdVelDriveController {
 public:
  static constexpr const char* kType = "diff_drive_controller/DiffDriveController";

  /// Its own keys (defaults as upstream's).
  struct Params {
    std::vector<std::string> left_wheels, right_wheels;
    double wheel_separation_multiplier = 1.0;
    double left_wheel_radius_multiplier = 1.0, right_wheel_radius_multiplier = 1.0;
    bool publish_wheel_joint_controller_state = false;
    double wheel_separation = 0.0, wheel_radius = 0.0;  // from the URDF when not given
  };
  /// What dynamic_reconfigure may change (cfg/DiffDriveController.cfg).
  struct DynamicParams {
    double left_wheel_radius_multiplier = 1.0, right_wheel_radius_multiplier = 1.0;
    double wheel_separation_multiplier = 1.0;
    double publish_rate = 50.0;
    bool enable_odom_tf = true;
  };

  /// Reads the parameters; the wheel separation and radius from context.robot_description when
  /// wheel_separation / wheel_radius are not given. Throws ControllerError with upstream's
  /// messages (a missing wheel param, #left wheels != #right wheels, no robot_description, a
  /// wheel joint not in it, a wheel link that is not a cylinder or sphere, a wheel joint without
  /// a velocity transmission).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  DiffDriveController(std::string name, Common common, Params params,
                      std::vector<JointHandle*> left, std::vector<JointHandle*> right);

  /// One wheel_joint_controller_state publication (publish_wheel_joint_controller_state:
  /// control_msgs/JointTrajectoryControllerState), as upstream's publishWheelData() fills it
  /// every update: the left wheels, then the right. Desired: velocities from the limited
  /// command, positions their running integral, accelerations (v - v_prev) * dt (upstream
  /// multiplies by the period), effort NaN; actual: the joints', accelerations from the change
  /// of velocity since the last update; error = desired - actual.
  struct WheelState {
    struct Point {
      std::vector<double> positions, velocities, accelerations, effort;
    };
    double t = 0.0;
    Point desired, actual, error;
  };
  /// Joint names of a WheelState, in its order.
  std::vector<std::string> wheelJointNames() const;
  /// The publications since the last call, oldest first (at most 100 kept).
  std::vector<WheelState> takeWheelStates();

  void starting(double time) override;
  std::vector<const JointHandle*> claimedJoints() const override;
  void brake() override;
  void setDynamicParams(const DynamicParams& p);
  DynamicParams dynamicParams() const;

  const Params& params() const { return params_; }
  /// Effective geometry: separation and radii times their multipliers.
  double wheelSeparation() const {
    return params_.wheel_separation_multiplier * params_.wheel_separation;
  }
  double leftWheelRadius() const {
    return params_.left_wheel_radius_multiplier * params_.wheel_radius;
  }
  double rightWheelRadius() const {
    return params_.right_wheel_radius_multiplier * params_.wheel_radius;
  }

 protected:
  bool updateOdometry(double time) override;
  void drive(double linear, double angular) override;
  void resetOdometry() override;

 private:
  void setWheels(double left, double right);

  void publishWheelData(double lin, double ang);

  Params params_;
  std::vector<JointHandle*> left_, right_;
  // publishWheelData()'s state: the desired positions it integrates and what it differences.
  std::vector<double> desired_positions_, vel_previous_;
  double vel_left_desired_previous_ = 0.0, vel_right_desired_previous_ = 0.0;
  double time_previous_ = 0.0;
  Outbox<WheelState> wheel_states_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_CONTROLLER_H
