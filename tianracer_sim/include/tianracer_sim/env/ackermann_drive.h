// The cmd_vel node's drive inside a simulation without ROS: an Ackermann command (speed,
// steering angle) goes through the same CmdVelProcessor (tianracer_control/cmd_vel.h) with the
// geometry and joint names found in the URDF as the node finds them, onto the controllers of
// the steering hinges and rear wheels. ROS-free.
#ifndef TIANRACER_SIM_ENV_ACKERMANN_DRIVE_H
#define TIANRACER_SIM_ENV_ACKERMANN_DRIVE_H

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <tianracer_control/cmd_vel.h>
#include <tianracer_control/joint_controllers.h>
#include <tianracer_control/urdf_geometry.h>

namespace tianracer_sim {

class AckermannDrive {
 public:
  /// As the cmd_vel node: joints by their seed names, found in the URDF prefixed or not
  /// (findModelNames), the geometry from the URDF (geometryFromUrdf; mesh URIs through
  /// `mesh_path`), and for each joint the first of `commanded` (controllers with a command, as
  /// {name, joint}) that drives it. Throws
  /// std::invalid_argument saying what the model lacks (a joint, a controller with a command
  /// for it). Warnings (names found under another name, defaults used) go to `warn`.
  AckermannDrive(const std::string& urdf_xml,
                 const std::vector<std::pair<std::string, std::string>>& commanded,
                 const tianracer_control::MeshPathResolver& mesh_path,
                 const tianracer_control::CmdVelLimits& limits = {},
                 const std::function<void(const std::string&)>& warn = {});

  const tianracer_control::AckermannGeometry& geometry() const { return geometry_; }
  const tianracer_control::CmdVelLimits& limits() const { return limits_; }
  /// Largest steering angles (bicycle model, rad) left and right (both positive).
  double maxSteeringLeft() const;
  double maxSteeringRight() const;
  /// Controllers of the left and right steering hinges, left and right rear wheels.
  const std::array<std::string, 4>& controllers() const { return controllers_; }

  /// An Ackermann drive command (ackermann_msgs/AckermannDrive: speed m/s, steering angle rad)
  /// at sim time t, and the controller commands of this tick (the node's timer at t):
  /// setAckermann() then update(t). Non-finite input is rejected (result.rejected, nothing
  /// changes, the previous command's tick is returned).
  tianracer_control::AckermannCommand command(double speed, double steering, double t,
                                              tianracer_control::AckermannDriveResult* result);
  /// Time went back (reset).
  void reset() { processor_->reset(); }

 private:
  tianracer_control::AckermannGeometry geometry_;
  tianracer_control::CmdVelLimits limits_;
  std::unique_ptr<tianracer_control::CmdVelProcessor> processor_;
  std::array<std::string, 4> controllers_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ENV_ACKERMANN_DRIVE_H
