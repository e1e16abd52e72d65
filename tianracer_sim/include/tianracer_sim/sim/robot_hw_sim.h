// RobotHwSim: what gazebo_ros_control's DefaultRobotHWSim (gazebo_ros_pkgs noetic-devel,
// gazebo_ros_control/src/default_robot_hw_sim.cpp, "DRS") does to a command between the
// controllers and the joint (docs/ros_controllers.md, "DefaultRobotHWSim"):
//  - registerJointLimits: limits from the URDF <limit>, overridden by the
//    <robot_namespace>/joint_limits/<joint> parameters (joint_limits_interface's
//    getJointLimits); with a URDF <safety_controller> the soft-limits handle of the joint's
//    command interface, else the saturation handle; enforced on every write with the period;
//  - initSim: a position or velocity joint with <robot_namespace>/gazebo_ros_control/pid_gains/
//    <joint> is driven by an effort PID clamped to the effort limit;
//  - writeSim: the emergency stop (GRCP's eStopTopic) holds position commands where the joints
//    were when it began, and writes 0 effort and 0 velocity.
// ROS-free: the host reads the parameters into RobotHwSimParams (the node from the parameter
// server, the Python env has none), Simulation::write sends the result to the physics.
#ifndef TIANRACER_SIM_SIM_ROBOT_HW_SIM_H
#define TIANRACER_SIM_SIM_ROBOT_HW_SIM_H

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <tianracer_control/controller_params.h>
#include <tianracer_control/joint_handle.h>
#include <tianracer_control/joint_limits.h>
#include <tianracer_control/pid.h>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

/// A robot's gazebo_ros_control parameters, as the host found them (absent: none).
struct RobotHwSimParams {
  /// The robot's namespace, for messages ("/tianracer").
  std::string ns;
  /// <ns>/joint_limits: a dictionary per joint with joint_limits_interface's keys
  /// (has_position_limits, min_position, max_position, has_velocity_limits, max_velocity,
  /// has_acceleration_limits, max_acceleration, has_jerk_limits, max_jerk, has_effort_limits,
  /// max_effort, angle_wraparound).
  tianracer_control::ParamValue joint_limits;
  /// <ns>/gazebo_ros_control/pid_gains: a dictionary per joint (p, i, d, i_clamp,
  /// i_clamp_min, i_clamp_max, antiwindup: control_toolbox::Pid::init).
  tianracer_control::ParamValue pid_gains;
  /// <ns>/steer_bot_hardware_gazebo and <ns>/gains: SteerBotHardwareGazebo's parameters
  /// (sim/steer_bot_hw_sim.h).
  tianracer_control::ParamValue steer_bot_hardware_gazebo;
  tianracer_control::ParamValue gains;
};

/// What the hardware sends to one joint after a write.
struct JointInfo;

/// A joint's handle as the hardware registers it: its name and interface, and, when the joint
/// is in the physics (`joint` not null), its URDF limits and whether it is continuous.
tianracer_control::JointHandle makeJointHandle(const std::string& name,
                                               tianracer_control::JointHandle::Interface iface,
                                               const JointInfo* joint);

struct JointDrive {
  enum class Mode {
    kEffort,    // value: N m / N (SetForce)
    kVelocity,  // value: rad/s, m/s, a motor capped at max_effort (SetParam "vel", "fmax")
    kPosition,  // value: rad, m (SetPosition; ours: a servo within one control period)
    kSetVelocity,  // value: rad/s, m/s, the joint's velocity set (Joint::SetVelocity), no motor
  };
  Mode mode = Mode::kEffort;
  double value = 0.0;
  /// The motor's cap for kVelocity and kPosition; < 0: the joint's default (physics).
  double max_effort = -1.0;
};

class RobotHwSim {
 public:
  /// DRS's control method of a joint.
  enum class Method { kEffort, kPosition, kPositionPid, kVelocity, kVelocityPid };
  /// Which joint_limits_interface handle enforces the joint's limits.
  enum class Limits { kNone, kSaturation, kSoftLimits };

  struct Joint {
    Method method = Method::kEffort;
    Limits limits_kind = Limits::kNone;
    tianracer_control::JointLimits limits;
    tianracer_control::SoftJointLimits soft;
    /// The URDF joint's type, for the PID's angular error (its position limits: `limits`).
    enum class Type { kOther, kRevolute, kContinuous };
    Type type = Type::kOther;
    /// DRS's effort limit: the limits' max_effort, unbounded (DBL_MAX) without one.
    double effortLimit() const {
      return limits.has_effort_limits ? limits.max_effort : std::numeric_limits<double>::max();
    }
    std::optional<tianracer_control::PositionSaturation> position_saturation;
    std::optional<tianracer_control::PositionSoftLimits> position_soft;
    std::optional<tianracer_control::VelocitySaturation> velocity_saturation;
    tianracer_control::Pid pid;
  };

  /// DRS initSim/registerJointLimits for each handle (the transmission order). `model`: the
  /// URDF (<limit>, <safety_controller>, the joint's type). Parameters of the wrong kind, not
  /// finite, or limits a handle cannot enforce are warned (naming <ns>/joint_limits/<joint> or
  /// <ns>/gazebo_ros_control/pid_gains/<joint> and the value) and left out.
  void init(const RobotModel& model, const std::vector<tianracer_control::JointHandle>& handles,
            const RobotHwSimParams& params, const WarningSink& warn);

  /// GRCP's eStopActive(): from the next write on.
  void setEStop(bool active) { e_stop_ = active; }
  bool eStop() const { return e_stop_; }
  /// True once after the stop was released: the host resets the controllers before their
  /// next update (controller_manager update(..., reset_controllers = true)).
  bool takeEStopReleased();

  /// DRS writeSim for handle k: the e-stop's held position, the limits (the handle's command
  /// becomes the limited one, as the handles write it back), then what the joint gets.
  /// `period`: the time since the last write (s, > 0).
  JointDrive write(size_t k, tianracer_control::JointHandle& h, double period);
  /// Called once before the writes of a control update with all handles (the stop's hold).
  void beginWrite(const std::vector<tianracer_control::JointHandle>& handles);

  /// After a reset (reset_world, controllers restarted): the limit handles' previous commands
  /// and the PIDs start anew.
  void reset();

  const std::vector<Joint>& joints() const { return joints_; }

 private:
  std::vector<Joint> joints_;
  bool e_stop_ = false;
  bool last_e_stop_ = false;   // DRS last_e_stop_active_: the hold is taken
  bool was_stopped_ = false;   // GRCP last_e_stop_active_: the release resets controllers
  std::vector<double> held_;   // DRS last_joint_position_command_
};

/// The error of a position PID (DRS writeSim POSITION_PID) from `position` to `command`:
/// revolute with limits spanning less than 2 pi: command - position (what
/// angles::shortest_angular_distance_with_limits gives when the command is within the limits);
/// continuous, or a revolute joint whose limits span 2 pi or more: the shortest angular
/// distance; prismatic: command - position.
double positionPidError(const RobotHwSim::Joint& joint, double position, double command);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_ROBOT_HW_SIM_H
