// What diff_drive_controller and ackermann_steering_controller share (ros_controllers
// noetic-devel, diff_drive_controller/src/diff_drive_controller.cpp and
// ackermann_steering_controller/src/ackermann_steering_controller.cpp: the same init() keys
// and the same update()): a cmd_vel command stamped on arrival and zeroed past cmd_vel_timeout,
// the linear/x and angular/z speed limiters, odometry published every 1/publish_rate, optionally
// as /tf. ROS-free; the topics are its ROS side's (ros/cmd_vel_drive_ros.cpp). A class gives its
// odometry step and how a limited command drives its joints.
//
// update() at time t, as upstream's:
//   odometry (open loop: the last limited command integrated; else the class's own step, which
//     may skip the whole update on a NaN joint position);
//   when t > last publication + 1/publish_rate: an odom sample (and a tf one when
//     enable_odom_tf) into the outbox, the last publication moving by the period;
//   the command (zero when older than cmd_vel_timeout), limited, to the class's drive().
#ifndef TIANRACER_CONTROL_CONTROLLERS_CMD_VEL_DRIVE_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_CMD_VEL_DRIVE_CONTROLLER_H

#include <array>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"
#include "tianracer_control/controllers/diff_drive_odometry.h"
#include "tianracer_control/controllers/outbox.h"
#include "tianracer_control/controllers/speed_limiter.h"

namespace tianracer_control {

class CmdVelDriveController : public Controller {
 public:
  /// The keys both controllers read (defaults as upstream's).
  struct Common {
    double publish_rate = 50.0;
    bool open_loop = false;
    int velocity_rolling_window_size = 10;
    double cmd_vel_timeout = 0.5;
    bool allow_multiple_cmd_vel_publishers = true;
    std::string base_frame_id = "base_link", odom_frame_id = "odom";
    bool enable_odom_tf = true;
    SpeedLimiter limiter_lin, limiter_ang;
    std::array<double, 6> pose_covariance_diagonal{}, twist_covariance_diagonal{};
    bool publish_cmd = false;  // diff_drive_controller only (ackermann's never reads it)
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

  /// Reads the shared keys. Throws ControllerError naming the key for a wrong kind or value.
  static Common readCommon(ControllerParams& params);

  CmdVelDriveController(std::string name, std::string type, Common common);

  void starting(double time) override;
  void update(double dt) final;
  /// Sim reset: the command is dropped, the odometry starts again at 0 (resetOdometry()).
  void reset() override;

  /// A cmd_vel (linear.x, angular.z); stamped with the time of the next update. A non-finite
  /// value: ignored, returns false.
  bool setCommand(double linear, double angular);
  /// The joints to rest (upstream's brake()).
  virtual void brake() = 0;

  const Common& common() const { return common_; }
  const DiffDriveOdometry& odometry() const { return odometry_; }
  /// The last command after the limiters.
  double lastLinear() const { return last0_.lin; }
  double lastAngular() const { return last0_.ang; }
  /// The publications update() produced since the last call, oldest first (at most 100 kept).
  std::vector<OdomSample> takeOdom();
  std::vector<CmdSample> takeCmdOut();

 protected:
  /// The closed-loop odometry step at `time`; false skips the rest of the update.
  virtual bool updateOdometry(double time) = 0;
  /// Writes the joints' commands for the limited command.
  virtual void drive(double linear, double angular) = 0;
  /// The odometry back to 0 at the joints' current positions.
  virtual void resetOdometry() = 0;

  Common common_;
  DiffDriveOdometry odometry_;
  double update_dt_ = 0.0;  // the period of the update that calls drive()

 private:
  struct Command {
    double lin = 0.0, ang = 0.0, stamp = 0.0;
  };
  Command command_;  // the latest cmd_vel
  bool stamp_pending_ = false;
  Command last0_, last1_;  // the last two limited commands
  double last_publish_ = 0.0;
  Outbox<OdomSample> odom_out_;
  Outbox<CmdSample> cmd_out_;
};

/// The wheel link's radius from its first collision cylinder (or sphere, when `sphere_ok`), as
/// diff_drive_controller's / ackermann_steering_controller's getWheelRadius(). Throws
/// ControllerError with upstream's messages.
double wheelRadiusFromUrdf(const urdf::ModelInterface& urdf, const std::string& joint,
                           const std::string& prefix, bool sphere_ok = true);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_CMD_VEL_DRIVE_CONTROLLER_H
