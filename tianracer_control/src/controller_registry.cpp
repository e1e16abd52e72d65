#include "tianracer_control/controller_registry.h"

#include <algorithm>

#include "tianracer_control/controllers/ackermann_steering_controller.h"
#include "tianracer_control/controllers/diff_drive_controller.h"
#include "tianracer_control/controllers/effort_joint_position_controller.h"
#include "tianracer_control/controllers/effort_joint_velocity_controller.h"
#include "tianracer_control/controllers/four_wheel_steering_controller.h"
#include "tianracer_control/controllers/gripper_action_controller.h"
#include "tianracer_control/controllers/forward_command_controller.h"
#include "tianracer_control/controllers/joint_group_controller.h"
#include "tianracer_control/controllers/joint_state_controller.h"
#include "tianracer_control/controllers/joint_trajectory_controller.h"

namespace tianracer_control {

const ControllerRegistry& builtinControllers() {
  static const ControllerRegistry registry = [] {
    ControllerRegistry r;
    r.add(JointStateController::kType, &JointStateController::create);
    r.add(EffortJointPositionController::kType, &EffortJointPositionController::create);
    r.add(EffortJointVelocityController::kType, &EffortJointVelocityController::create);
    using Iface = JointHandle::Interface;
    r.add(ForwardCommandController::kEffortType, &ForwardCommandController::create<Iface::kEffort>);
    r.add(ForwardCommandController::kVelocityType,
          &ForwardCommandController::create<Iface::kVelocity>);
    r.add(ForwardCommandController::kPositionType,
          &ForwardCommandController::create<Iface::kPosition>);
    r.add(VelocityJointPositionController::kType, &VelocityJointPositionController::create);
    r.add(JointGroupController::kEffortType, &JointGroupController::create<Iface::kEffort>);
    r.add(JointGroupController::kVelocityType, &JointGroupController::create<Iface::kVelocity>);
    r.add(JointGroupController::kPositionType, &JointGroupController::create<Iface::kPosition>);
    r.add(JointGroupController::kEffortPositionType, &JointGroupController::createEffortPosition);
    r.add(DiffDriveController::kType, &DiffDriveController::create);
    r.add(AckermannSteeringController::kType, &AckermannSteeringController::create);
    r.add(FourWheelSteeringController::kType, &FourWheelSteeringController::create);
    r.add(JointTrajectoryController::kPositionType,
          &JointTrajectoryController::create<Iface::kPosition>);
    r.add(JointTrajectoryController::kVelocityType,
          &JointTrajectoryController::create<Iface::kVelocity>);
    r.add(JointTrajectoryController::kEffortType,
          &JointTrajectoryController::create<Iface::kEffort>);
    r.add(GripperActionController::kPositionType,
          &GripperActionController::create<Iface::kPosition>);
    r.add(GripperActionController::kEffortType, &GripperActionController::create<Iface::kEffort>);
    return r;
  }();
  return registry;
}

void ControllerRegistry::add(const std::string& type, ControllerFactory factory) {
  for (auto& entry : factories_) {
    if (entry.first == type) {
      entry.second = factory;
      return;
    }
  }
  factories_.emplace_back(type, factory);
}

std::vector<std::string> ControllerRegistry::types() const {
  std::vector<std::string> out;
  for (const auto& entry : factories_) out.push_back(entry.first);
  return out;
}

bool ControllerRegistry::has(const std::string& type) const {
  return std::any_of(factories_.begin(), factories_.end(),
                     [&](const auto& entry) { return entry.first == type; });
}

std::unique_ptr<Controller> ControllerRegistry::create(const ControllerSpec& spec,
                                                       std::map<std::string, JointHandle*>& joints,
                                                       const WarningSink& warn,
                                                       const urdf::ModelInterface* description) const {
  ControllerParams params(spec);
  const std::string pre = params.prefix();
  if (spec.name.empty()) throw ControllerError(pre + "the controller name is empty");
  if (spec.type.empty()) throw ControllerError(pre + "no type given (parameter 'type')");
  const auto it = std::find_if(factories_.begin(), factories_.end(),
                               [&](const auto& entry) { return entry.first == spec.type; });
  if (it == factories_.end()) {
    std::string known;
    for (const auto& entry : factories_) known += (known.empty() ? "" : ", ") + entry.first;
    throw ControllerError(pre + "unknown type '" + spec.type + "' (known types: " +
                          known + ")");
  }
  ControllerContext context{params, joints, warn, description};
  std::unique_ptr<Controller> controller = it->second(context);
  if (warn) {
    for (const std::string& key : params.unread()) {
      warn(pre + "key '" + key + "' is not used by " + spec.type + ", ignored");
    }
  }
  return controller;
}

}  // namespace tianracer_control
