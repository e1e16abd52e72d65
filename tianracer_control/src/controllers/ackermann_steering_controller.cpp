#include "tianracer_control/controllers/ackermann_steering_controller.h"

#include <cmath>
#include <sstream>

#include <urdf_model/model.h>

namespace tianracer_control {

std::unique_ptr<Controller> AckermannSteeringController::create(ControllerContext& context) {
  ControllerParams& params = context.params;
  const std::string pre = params.prefix();
  Params p;
  p.rear_wheel = params.text("rear_wheel").value_or(p.rear_wheel);
  p.front_steer = params.text("front_steer").value_or(p.front_steer);
  Common common = readCommon(params);
  p.wheel_separation_h_multiplier = params.positiveNumber("wheel_separation_h_multiplier", 1.0);
  p.wheel_radius_multiplier = params.positiveNumber("wheel_radius_multiplier", 1.0);
  p.steer_pos_multiplier = params.number("steer_pos_multiplier").value_or(1.0);
  if (!std::isfinite(p.steer_pos_multiplier)) {
    throw ControllerError(pre + "steer_pos_multiplier must be a finite number");
  }
  // setOdomParamsFromUrdf()
  const std::optional<double> separation = params.number("wheel_separation_h");
  const std::optional<double> radius = params.number("wheel_radius");
  if (!separation || !radius) {
    const urdf::ModelInterface* urdf = context.robot_description;
    if (!urdf) {  // sic: upstream's text
      throw ControllerError(pre + "Robot descripion couldn't be retrieved from param server.");
    }
    const urdf::JointConstSharedPtr rear = urdf->getJoint(p.rear_wheel);
    const urdf::JointConstSharedPtr steer = urdf->getJoint(p.front_steer);
    if (!separation) {
      for (const auto& [joint, name] : {std::pair(rear, p.rear_wheel),
                                        std::pair(steer, p.front_steer)}) {
        if (!joint) {
          throw ControllerError(pre + name + " couldn't be retrieved from model description");
        }
      }
      p.wheel_separation_h = std::fabs(rear->parent_to_joint_origin_transform.position.x -
                                       steer->parent_to_joint_origin_transform.position.x);
    }
    if (!radius) {
      if (!rear) {
        throw ControllerError(pre + p.rear_wheel + " couldn't be retrieved from model description");
      }
      p.wheel_radius = wheelRadiusFromUrdf(*urdf, p.rear_wheel, pre, false);
    }
  }
  if (separation) p.wheel_separation_h = *separation;
  if (radius) p.wheel_radius = *radius;
  for (const auto& [value, key] : {std::pair(p.wheel_separation_h, "wheel_separation_h"),
                                   std::pair(p.wheel_radius, "wheel_radius")}) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      std::ostringstream os;
      os << pre << key << " must be positive, got " << value;
      throw ControllerError(os.str());
    }
  }
  JointHandle* rear = findJoint(context, p.rear_wheel, JointHandle::Interface::kVelocity);
  JointHandle* steer = findJoint(context, p.front_steer, JointHandle::Interface::kPosition);
  return std::make_unique<AckermannSteeringController>(params.name(), std::move(common),
                                                       std::move(p), rear, steer);
}

AckermannSteeringController::AckermannSteeringController(std::string name, Common common,
                                                         Params params, JointHandle* rear,
                                                         JointHandle* steer)
    : CmdVelDriveController(std::move(name), kType, std::move(common)),
      params_(std::move(params)),
      rear_(rear),
      steer_(steer) {}

void AckermannSteeringController::brake() {
  rear_->command = 0.0;
  steer_->command = 0.0;
}

void AckermannSteeringController::resetOdometry() {
  odometry_.resetPose(0.0, 0.0);
  rear_old_pos_ = rear_->position * params_.wheel_radius_multiplier * params_.wheel_radius;
}

bool AckermannSteeringController::updateOdometry(double time) {
  const double wheel_pos = rear_->position, steer_pos = steer_->position;
  if (std::isnan(wheel_pos) || std::isnan(steer_pos)) return false;
  const double radius = params_.wheel_radius_multiplier * params_.wheel_radius;
  const double separation = params_.wheel_separation_h_multiplier * params_.wheel_separation_h;
  const double travel = wheel_pos * radius;
  const double linear = travel - rear_old_pos_;
  rear_old_pos_ = travel;
  const double angular =
      std::tan(steer_pos * params_.steer_pos_multiplier) * linear / separation;
  odometry_.integrate(linear, angular, time);
  return true;
}

void AckermannSteeringController::drive(double linear, double angular) {
  rear_->command = linear / params_.wheel_radius;  // omega = linear_vel / radius
  steer_->command = angular;  // the hardware (DefaultRobotHWSim) enforces the joint's limits
}

}  // namespace tianracer_control
