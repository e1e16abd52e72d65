// ackermann_steering_controller/AckermannSteeringController (ros_controllers noetic-devel,
// ackermann_steering_controller/src/ackermann_steering_controller.cpp, src/odometry.cpp): one
// rear wheel (velocity) and one front steer joint (position), a bicycle model. Over what it
// shares with diff_drive_controller (cmd_vel_drive_controller.h):
//   keys: rear_wheel (default rear_wheel_joint), front_steer (default front_steer_joint),
//     wheel_separation_h and wheel_radius (from the URDF when not given: |x(rear wheel joint
//     origin) - x(front steer joint origin)|, each in its parent link; the rear wheel link's
//     collision cylinder), wheel_separation_h_multiplier, wheel_radius_multiplier,
//     steer_pos_multiplier;
//   odometry: linear = rear wheel travel (position x wheel radius), angular = tan(steer
//     position x steer_pos_multiplier) linear / wheel_separation_h;
//   commands: rear wheel velocity = linear.x / wheel_radius (the radius without its
//     multiplier, as upstream), front steer position = angular.z (the command's angular.z IS
//     the steering angle, upstream's convention).
#ifndef TIANRACER_CONTROL_CONTROLLERS_ACKERMANN_STEERING_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_ACKERMANN_STEERING_CONTROLLER_H

#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controllers/cmd_vel_drive_controller.h"

namespace tianracer_control {

class AckermannSteeringController : public CmdVelDriveController {
 public:
  static constexpr const char* kType = "ackermann_steering_controller/AckermannSteeringController";

  struct Params {
    std::string rear_wheel = "rear_wheel_joint", front_steer = "front_steer_joint";
    double wheel_separation_h = 0.0, wheel_radius = 0.0;
    double wheel_separation_h_multiplier = 1.0, wheel_radius_multiplier = 1.0;
    double steer_pos_multiplier = 1.0;
  };

  /// Throws ControllerError with upstream's messages (no robot_description, a joint not in it,
  /// a rear wheel link that is not a cylinder) or for a joint without the interface it needs.
  static std::unique_ptr<Controller> create(ControllerContext& context);

  AckermannSteeringController(std::string name, Common common, Params params, JointHandle* rear,
                              JointHandle* steer);

  std::vector<const JointHandle*> claimedJoints() const override { return {rear_, steer_}; }
  void brake() override;
  const Params& params() const { return params_; }

 protected:
  bool updateOdometry(double time) override;
  void drive(double linear, double angular) override;
  void resetOdometry() override;

 private:
  Params params_;
  JointHandle* rear_;
  JointHandle* steer_;
  double rear_old_pos_ = 0.0;  // rear wheel travel at the last update (m)
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_ACKERMANN_STEERING_CONTROLLER_H
