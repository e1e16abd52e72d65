// The JointGroup controllers of ros_controllers (noetic-devel): a list of joints (`joints`), one
// command per joint on <controller>/command (std_msgs/Float64MultiArray).
//   effort_controllers/JointGroupEffortController      forward_command_controller's
//   velocity_controllers/JointGroupVelocityController   ForwardJointGroupCommandController over
//   position_controllers/JointGroupPositionController   the effort, velocity, position interface
//   effort_controllers/JointGroupPositionController     effort = PID(position error) per joint,
//                                                        gains under <joint>/pid
// As the single-joint forwarders here, commands are clamped to the joint's URDF limit of its
// interface (the position controllers' targets to the position limits).
#ifndef TIANRACER_CONTROL_CONTROLLERS_JOINT_GROUP_CONTROLLER_H
#define TIANRACER_CONTROL_CONTROLLERS_JOINT_GROUP_CONTROLLER_H

#include <memory>
#include <string>
#include <vector>

#include "tianracer_control/controller.h"
#include "tianracer_control/controllers/pid_state.h"
#include "tianracer_control/pid.h"

namespace tianracer_control {

class JointGroupController : public Controller {
 public:
  static constexpr const char* kEffortType = "effort_controllers/JointGroupEffortController";
  static constexpr const char* kVelocityType = "velocity_controllers/JointGroupVelocityController";
  static constexpr const char* kPositionType = "position_controllers/JointGroupPositionController";
  static constexpr const char* kEffortPositionType =
      "effort_controllers/JointGroupPositionController";

  /// Reads joints (a non-empty list of joints with the interface `I`).
  template <JointHandle::Interface I>
  static std::unique_ptr<Controller> create(ControllerContext& context);
  /// Reads joints (effort joints) and <joint>/pid for each.
  static std::unique_ptr<Controller> createEffortPosition(ControllerContext& context);

  /// pids: one per joint for the PID type, empty for the forwarders.
  JointGroupController(std::string name, std::string type, std::vector<JointHandle*> joints,
                       std::vector<Pid> pids);

  std::vector<const JointHandle*> claimedJoints() const override;
  const std::vector<JointHandle*>& joints() const { return joints_; }
  /// The targets, one per joint.
  const std::vector<double>& commands() const { return commands_; }

  /// Position targets: the current positions (clamped to the limits); others: 0. PIDs reset.
  void starting(double time) override;
  void update(double dt) override;
  void reset() override;
  /// One value per joint. "" when taken; else why not (nothing changes): upstream's "Dimension
  /// of command (3) does not match number of joints (2)! Not executing!", or a non-finite value.
  std::string setCommands(const std::vector<double>& values);

 private:
  bool positionTargets() const;
  double clamp(const JointHandle& joint, double value) const;

  std::vector<JointHandle*> joints_;
  std::vector<Pid> pids_;
  std::vector<double> commands_;
};

/// velocity_controllers/JointPositionController: velocity = PID(position error) (the shortest
/// way round for a continuous joint), derivative from successive errors (control_toolbox's
/// computeCommand(error, dt), as upstream calls it for a position-only command); the target
/// clamped to the position limits, the velocity to +-velocity_limit. Gains under pid/.
class VelocityJointPositionController : public SingleJointController, public PidStateSource {
 public:
  static constexpr const char* kType = "velocity_controllers/JointPositionController";
  static std::unique_ptr<Controller> create(ControllerContext& context);

  VelocityJointPositionController(std::string name, JointHandle* joint, const Pid& pid);
  void starting(double time) override;
  void update(double dt) override;
  void reset() override { pid_.reset(); }
  bool setCommand(double value) override;

 private:
  Pid pid_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_CONTROLLERS_JOINT_GROUP_CONTROLLER_H
