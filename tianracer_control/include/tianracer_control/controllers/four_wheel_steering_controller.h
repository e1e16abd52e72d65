// four_wheel_steering_controller/FourWheelSteeringController (ros_controllers noetic-devel,
// four_wheel_steering_controller/src/four_wheel_steering_controller.cpp and src/odometry.cpp),
// without ROS: two steered axles of two wheels each (front_wheel, rear_wheel: velocity joints,
// left then right; front_steering, rear_steering: position joints), driven either by a twist
// (cmd_vel: linear.x, angular.z; the rear steers opposite to the front) or by a
// four_wheel_steering_msgs/FourWheelSteering (speed and the two virtual axle angles), whichever
// arrived last; the odometry from the four wheel speeds and the two axles' virtual angles. Its
// ROS side is ros/four_wheel_steering_ros.cpp.
#ifndef TIANRACER_CONTROL_CONTROLLERS_FOUR_WHEEL_STEERING_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_FOUR_WHEEL_STEERING_CONTROLLER_H

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controllers/cmd_vel_drive_controller.h"
#include "tianracer_control/controllers/diff_drive_odometry.h"
#include "tianracer_control/controllers/outbox.h"

namespace tianracer_control {

/// src/odometry.cpp: the body's velocity from the wheel speeds (rad/s) and the virtual front
/// and rear steering angles, integrated in x, y and heading; the speed's rolling-mean
/// acceleration and jerk and the angles' rolling-mean rates (for odom_steer).
class FourWheelSteeringOdometry {
 public:
  explicit FourWheelSteeringOdometry(std::size_t window = 10) { setWindow(window); }
  void setWindow(std::size_t window);
  /// steering_track = track - 2 wheel_steering_y_offset.
  void setWheelParams(double steering_track, double wheel_steering_y_offset, double wheel_radius,
                      double wheel_base);
  void init(double time);
  /// Upstream's update(); false when less than 0.1 ms passed (nothing integrated).
  bool update(double fl_speed, double fr_speed, double rl_speed, double rr_speed,
              double front_steering, double rear_steering, double time);
  void resetPose() { x_ = y_ = heading_ = 0.0; }

  double x() const { return x_; }
  double y() const { return y_; }
  double heading() const { return heading_; }
  double linear() const { return linear_; }
  double linearX() const { return linear_x_; }
  double linearY() const { return linear_y_; }
  double angular() const { return angular_; }
  double linearAcceleration() const { return accel_.mean(); }
  double linearJerk() const { return jerk_.mean(); }
  double frontSteerVel() const { return front_steer_vel_.mean(); }
  double rearSteerVel() const { return rear_steer_vel_.mean(); }

 private:
  double last_time_ = 0.0;
  double x_ = 0.0, y_ = 0.0, heading_ = 0.0;
  double linear_ = 0.0, linear_x_ = 0.0, linear_y_ = 0.0, angular_ = 0.0;
  double steering_track_ = 0.0, wheel_steering_y_offset_ = 0.0, wheel_radius_ = 0.0, wheel_base_ = 0.0;
  std::size_t window_ = 10;
  RollingMean accel_, jerk_, front_steer_vel_, rear_steer_vel_;
  double linear_vel_prev_ = 0.0, linear_accel_prev_ = 0.0;
  double front_steer_prev_ = 0.0, rear_steer_prev_ = 0.0;
};

class FourWheelSteeringController : public Controller {
 public:
  static constexpr const char* kType = "four_wheel_steering_controller/FourWheelSteeringController";

  struct Params {
    std::array<std::string, 2> front_wheels, rear_wheels, front_steering, rear_steering;  // left, right
    double track = 0.0, wheel_radius = 0.0, wheel_base = 0.0;  // from the URDF when not given
    double wheel_steering_y_offset = 0.0;                      // always from the URDF
  };
  /// One odom (and /tf when `tf`) and odom_steer publication.
  struct OdomSample {
    double t, x, y, heading, linear_x, linear_y, angular;
    bool tf;
    double speed, acceleration, jerk, front_steering, front_steering_velocity, rear_steering,
        rear_steering_velocity;
  };

  /// Reads the parameters (geometry from context.robot_description when not given). Throws
  /// ControllerError with upstream's messages (a missing wheel param, not two wheels or two
  /// steering joints per axle, a joint not in the URDF, a wheel link that is not a cylinder).
  static std::unique_ptr<Controller> create(ControllerContext& context);

  FourWheelSteeringController(std::string name, CmdVelDriveController::Common common, Params params,
                              std::array<JointHandle*, 4> wheels, std::array<JointHandle*, 4> steering);

  std::vector<const JointHandle*> claimedJoints() const override;
  void starting(double time) override;
  void update(double dt) override;
  void reset() override;

  /// cmd_vel (linear.x, linear.y, angular.z): false for a NaN linear.x or angular.z (ignored).
  bool setTwist(double linear_x, double linear_y, double angular);
  /// cmd_four_wheel_steering: false for a NaN value (ignored).
  bool setFourWheelSteering(double front_steering, double rear_steering, double speed);
  /// The joints to rest: wheels 0 rad/s, steering 0 rad.
  void brake();

  const Params& params() const { return params_; }
  const CmdVelDriveController::Common& common() const { return common_; }
  const FourWheelSteeringOdometry& odometry() const { return odometry_; }
  /// The publications since the last call, oldest first (at most 100 kept).
  std::vector<OdomSample> takeOdom();

 private:
  void updateOdometry(double time);
  void updateCommand(double time, double dt);

  struct Twist {
    double lin_x = 0.0, lin_y = 0.0, ang = 0.0, stamp = 0.0;
  };
  struct FourWs {
    double lin = 0.0, front_steering = 0.0, rear_steering = 0.0, stamp = 0.0;
  };

  CmdVelDriveController::Common common_;
  Params params_;
  std::array<JointHandle*, 4> wheels_;    // front left, front right, rear left, rear right
  std::array<JointHandle*, 4> steering_;  // the same order
  FourWheelSteeringOdometry odometry_;
  Twist twist_;
  FourWs four_ws_;
  bool twist_pending_ = false, four_ws_pending_ = false;
  Twist last0_, last1_;  // the last two limited commands (lin_x, ang)
  double last_publish_ = 0.0;
  Outbox<OdomSample> odom_out_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_FOUR_WHEEL_STEERING_CONTROLLER_H
