// diff_drive_controller/DiffDriveController (ros_controllers noetic-devel,
// diff_drive_controller/src/diff_drive_controller.cpp), without ROS: its parameters, its
// odometry (diff_drive_odometry.h), its speed limiters (speed_limiter.h) and its update(). The
// topics (cmd_vel, odom, /tf, cmd_vel_out) are its ROS side's (ros/diff_drive_ros.cpp), which
// hands commands in (setCommand) and sends what update() leaves in the outbox.
//
// update() at time t, as upstream:
//   odometry: open loop from the last limited command, else from the mean position of each
//     side's wheels (skid steer: several wheels a side); a NaN wheel position skips the update;
//   every publish period (t > last publication + 1/publish_rate): an odom sample (and a tf one
//     when enable_odom_tf) into the outbox;
//   the command (zero when older than cmd_vel_timeout) limited by linear/x and angular/z, then
//     left = (lin - ang ws / 2) / lwr, right = (lin + ang ws / 2) / rwr to every wheel of a side
//     (ws, lwr, rwr: wheel_separation and wheel_radius times their multipliers).
#ifndef TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_CONTROLLER_H

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"
#include "tianracer_control/controllers/diff_drive_odometry.h"
#include "tianracer_control/controllers/speed_limiter.h"

namespace tianracer_control {

/// The wheel joints' names from `key` (left_wheel, right_wheel): a string or a non-empty list
/// of strings (getWheelNames). Throws ControllerError with upstream's messages.
std::vector<std::string> readWheelNames(ControllerParams& params, const std::string& key);

/// wheel_radius from a wheel link's first collision geometry, a cylinder or a sphere
/// (getWheelRadius). Throws ControllerError with upstream's messages.
double wheelRadiusFromUrdf(const urdf::ModelInterface& urdf, const std::string& joint,
                           const std::string& prefix);

class DiffDriveController : public Controller {
 public:
  static constexpr const char* kType = "diff_drive_controller/DiffDriveController";

  /// Everything init() reads (defaults as upstream's).
  struct Params {
    std::vector<std::string> left_wheels, right_wheels;
    double publish_rate = 50.0;
    bool open_loop = false;
    double wheel_separation_multiplier = 1.0;
    double left_wheel_radius_multiplier = 1.0, right_wheel_radius_multiplier = 1.0;
    int velocity_rolling_window_size = 10;
    double cmd_vel_timeout = 0.5;
    bool allow_multiple_cmd_vel_publishers = true;
    std::string base_frame_id = "base_link", odom_frame_id = "odom";
    bool enable_odom_tf = true;
    SpeedLimiter limiter_lin, limiter_ang;
    bool publish_cmd = false;
    bool publish_wheel_joint_controller_state = false;
    double wheel_separation = 0.0, wheel_radius = 0.0;  // from the URDF when not given
    std::array<double, 6> pose_covariance_diagonal{}, twist_covariance_diagonal{};
  };
  /// What dynamic_reconfigure may change (cfg/DiffDriveController.cfg).
  struct DynamicParams {
    double left_wheel_radius_multiplier = 1.0, right_wheel_radius_multiplier = 1.0;
    double wheel_separation_multiplier = 1.0;
    double publish_rate = 50.0;
    bool enable_odom_tf = true;
  };
  /// One odometry publication (odom, and /tf when `tf`).
  struct OdomSample {
    double t, x, y, heading, linear, angular;
    bool tf;
  };
  /// One cmd_vel_out publication: the command after the limiters.
  struct CmdSample {
    double t, linear, angular;
  };

  /// Reads the parameters; the wheel separation and radius from context.robot_description when
  /// wheel_separation / wheel_radius are not given. Throws ControllerError with upstream's
  /// messages (a missing wheel param, #left wheels != #right wheels, no robot_description, a
  /// wheel joint not in it, a wheel link that is not a cylinder or sphere, a wheel joint without
  /// a velocity transmission).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  DiffDriveController(std::string name, Params params, std::vector<JointHandle*> left,
                      std::vector<JointHandle*> right);

  std::vector<const JointHandle*> claimedJoints() const override;
  void starting(double time) override;
  void update(double dt) override;
  /// Sim reset: the odometry starts again at 0 from the wheels' current positions, the command
  /// is dropped.
  void reset() override;

  /// A cmd_vel (linear.x, angular.z); stamped with the time of the next update. A non-finite
  /// value: ignored, returns false (upstream: "Received NaN in velocity command. Ignoring.").
  bool setCommand(double linear, double angular);
  /// Zero wheel velocities now (upstream's brake(): several cmd_vel publishers when they are
  /// not allowed).
  void brake();
  void setDynamicParams(const DynamicParams& p);
  DynamicParams dynamicParams() const;

  const Params& params() const { return params_; }
  const DiffDriveOdometry& odometry() const { return odometry_; }
  /// Effective geometry: separation and radii times their multipliers.
  double wheelSeparation() const { return params_.wheel_separation_multiplier * params_.wheel_separation; }
  double leftWheelRadius() const { return params_.left_wheel_radius_multiplier * params_.wheel_radius; }
  double rightWheelRadius() const { return params_.right_wheel_radius_multiplier * params_.wheel_radius; }
  /// The last command after the limiters (linear, angular).
  double lastLinear() const { return last0_.lin; }
  double lastAngular() const { return last0_.ang; }

  /// The publications update() produced since the last call, oldest first.
  std::vector<OdomSample> takeOdom();
  std::vector<CmdSample> takeCmdOut();

 private:
  struct Command {
    double lin = 0.0, ang = 0.0, stamp = 0.0;
  };
  void setWheels(double left, double right);

  Params params_;
  std::vector<JointHandle*> left_, right_;
  DiffDriveOdometry odometry_;
  Command command_;          // the latest cmd_vel
  bool stamp_pending_ = false;
  Command last0_, last1_;    // the last two limited commands
  double last_publish_ = 0.0;
  std::vector<OdomSample> odom_out_;
  std::vector<CmdSample> cmd_out_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_DIFF_DRIVE_CONTROLLER_H
