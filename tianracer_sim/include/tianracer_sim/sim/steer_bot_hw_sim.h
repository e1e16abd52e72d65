// SteerBotHwSim: the robotSimType steer_bot_hardware_gazebo/SteerBotHardwareGazebo (CIR-KIT's
// steer_drive_ros, melodic-devel 75c3688, steer_bot_hardware_gazebo/src/
// steer_bot_hardware_gazebo.cpp, "SBH"; docs/real_robots.md, "An Ackermann robot"), used in
// place of DefaultRobotHWSim (sim/robot_hw_sim.h) when the gazebo_ros_control plugin names it.
// A bicycle's two joints for the controller (upstream's `rear_wheel`, `front_steer`: joints no
// physics drives) fanned out onto the robot's wheel and steer joints (upstream's "virtual"
// joints, the ones Gazebo simulates):
//  - initSim (SBH 24-98): <ns>/steer_bot_hardware_gazebo/{rear_wheel, front_steer,
//    virtual_rear_wheels, virtual_front_wheels, virtual_front_steers, wheel_separation_w,
//    wheel_separation_h, enable_ackermann_link} and the PID gains <ns>/gains/<rear wheel>
//    (control_toolbox::Pid::init: p required; read, but no write uses them, as upstream);
//    handles in SBH's registration order (RegisterSteerInterface, then RegisterWheelInterface):
//    front_steer, the two steers (position), rear_wheel, the two rear wheels (velocity), the
//    two front wheels (state only upstream; here velocity handles whose command is not used);
//  - readSim (SBH 100-140, 469-481): each driven joint's position accumulated by the shortest
//    angular distance to the physics', its velocity and effort; front_steer's state the mean of
//    the two steers';
//  - writeSim (SBH 142-261): the four wheels get SetVelocity(rear_wheel's command); the right
//    and left steers SetPosition of the Ackermann link's angles atan2(2h tan d, 2h +- w/2 tan d)
//    (without the link: d and 2 d, as upstream); then front_steer's position becomes its
//    command and rear_wheel's position and velocity the mean of the rear wheels'. Written on
//    every control update whether or not a controller claims the joints (upstream writes its
//    commands, 0 until a controller runs, on every step).
// The e-stop does nothing here (RobotHWSim::eStopActive's default, which SBH keeps).
// ROS-free: the host reads the parameters into RobotHwSimParams.
#ifndef TIANRACER_SIM_SIM_STEER_BOT_HW_SIM_H
#define TIANRACER_SIM_SIM_STEER_BOT_HW_SIM_H

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <tianracer_control/joint_handle.h>
#include <tianracer_control/pid.h>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/sim/robot_hw_sim.h"

namespace tianracer_sim {

class PhysicsRobot;

/// The <robotSimType> that selects SteerBotHwSim.
constexpr const char* kSteerBotHardwareGazebo = "steer_bot_hardware_gazebo/SteerBotHardwareGazebo";

class SteerBotHwSim {
 public:
  /// Handle indices, SBH's registration order.
  enum Handle : size_t {
    kFrontSteer, kRightSteer, kLeftSteer, kRearWheel, kRightRearWheel, kLeftRearWheel,
    kRightFrontWheel, kLeftFrontWheel, kHandleCount
  };

  /// initSim: reads the parameters and builds the robot's handles (`handle_joint`: the physics
  /// joint of each; -1 for rear_wheel and front_steer, which SBH never reads or writes even
  /// where the model has such a joint). A parameter missing, of the wrong kind or value, a
  /// joint the robot does not have, a PID without p throw ModelError naming the plugin, the
  /// parameter or joint and the value (upstream: a garbage value, an out-of-range index, or
  /// initSim failing and gazebo_ros_control's "Could not initialize robot simulation
  /// interface"). Warnings (`warn`): SBH's "Joint limits won't be enforced" for a steer
  /// without <limit> and <safety_controller>; enable_ackermann_link not set.
  void init(const RobotModel& model, const PhysicsRobot& robot, const RobotHwSimParams& params,
            const WarningSink& warn, std::vector<tianracer_control::JointHandle>* handles,
            std::vector<int>* handle_joint);

  /// readSim, after the host put each driven joint's physics state into its handle.
  void read(std::vector<tianracer_control::JointHandle>& handles);

  /// writeSim: what each driven joint gets (physics joint index, drive), from the handles'
  /// commands; updates front_steer's and rear_wheel's state. A command that is not finite is
  /// not applied (its joints keep what they had). The returned storage is reused.
  const std::vector<std::pair<int, JointDrive>>& write(
      std::vector<tianracer_control::JointHandle>& handles);

  bool ackermannLink() const { return ackermann_link_; }
  double wheelSeparationW() const { return w_; }
  double wheelSeparationH() const { return h_; }
  /// The PIDs SBH builds from <ns>/gains/<rear wheel> (right, left); unused, as upstream's.
  const std::array<tianracer_control::Pid, 2>& pids() const { return pids_; }

 private:
  std::array<int, kHandleCount> joint_{};
  bool ackermann_link_ = true;
  double w_ = 0.0, h_ = 0.0;
  std::array<tianracer_control::Pid, 2> pids_;
  std::vector<double> position_;  // SBH's accumulated positions, per handle
  std::vector<std::pair<int, JointDrive>> drives_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_STEER_BOT_HW_SIM_H
