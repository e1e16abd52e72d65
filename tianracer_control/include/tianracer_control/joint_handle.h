// The simulator's hardware abstraction for one joint (ros_control's JointHandle, flattened).
#ifndef TIANRACER_CONTROL_JOINT_HANDLE_H
#define TIANRACER_CONTROL_JOINT_HANDLE_H

#include <string>

namespace tianracer_control {

/// One actuated joint. The simulator fills the state and limits (read), runs the controllers,
/// then applies `command` (write) according to `interface`.
struct JointHandle {
  std::string name;
  double position = 0.0;  // rad or m
  double velocity = 0.0;  // rad/s or m/s
  double effort = 0.0;    // N m or N

  /// The hardwareInterface of the joint's transmission.
  enum class Interface { kEffort, kVelocity, kPosition };
  Interface interface = Interface::kEffort;

  /// Written by the controller: effort (N m / N) for kEffort, velocity (rad/s, m/s) for
  /// kVelocity, position (rad, m) for kPosition.
  double command = 0.0;

  // From the URDF.
  bool has_position_limits = false;  // revolute/prismatic with <limit lower upper>
  double lower = 0.0;
  double upper = 0.0;
  double velocity_limit = 0.0;  // 0 = none
  double effort_limit = 0.0;    // 0 = none
  /// A continuous joint: position errors take the shorter way round the circle.
  bool continuous = false;
};

const char* toString(JointHandle::Interface iface);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_JOINT_HANDLE_H
