#include "tianracer_sim/env/ackermann_drive.h"

#include <stdexcept>

namespace tianracer_sim {

namespace tc = tianracer_control;

AckermannDrive::AckermannDrive(const std::string& urdf_xml,
                               const std::vector<std::pair<std::string, std::string>>& commanded,
                               const tc::MeshPathResolver& mesh_path,
                               const tc::CmdVelLimits& limits,
                               const std::function<void(const std::string&)>& warn)
    : limits_(limits) {
  const tc::ModelNames names = tc::findModelNames(urdf_xml, tc::AckermannJointNames());
  if (warn) {
    for (const std::string& w : names.found) warn("Ackermann drive: " + w);
  }
  const std::array<std::string, 4> joints = {names.joints.left_hinge, names.joints.right_hinge,
                                             names.joints.left_rear_wheel,
                                             names.joints.right_rear_wheel};
  std::string missing;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    for (const auto& [name, joint] : commanded) {
      if (joint == joints[k]) {
        controllers_[k] = name;
        break;
      }
    }
    if (controllers_[k].empty()) missing += (missing.empty() ? "" : ", ") + joints[k];
  }
  if (!missing.empty()) {
    std::string why;
    for (const std::string& w : names.warnings) why += "; " + w;
    throw std::invalid_argument(
        "no Ackermann drive: no controller with a command drives joint(s) " + missing +
        " (the cmd_vel node's steering hinges and rear wheels)" + why);
  }
  const tc::UrdfGeometry urdf =
      tc::geometryFromUrdf(urdf_xml, names.joints, names.base_link, mesh_path);
  const tc::ResolvedGeometry resolved = tc::resolveGeometry({}, &urdf);
  if (warn) {
    for (const std::string& w : resolved.warnings) warn("Ackermann drive: geometry: " + w);
  }
  geometry_ = resolved.geometry;
  processor_ = std::make_unique<tc::CmdVelProcessor>(geometry_, tc::AckermannOptions(), limits_);
}

double AckermannDrive::maxSteeringLeft() const { return tc::maxBicycleAngleLeft(geometry_); }
double AckermannDrive::maxSteeringRight() const { return tc::maxBicycleAngleRight(geometry_); }

tc::AckermannCommand AckermannDrive::command(double speed, double steering, double t,
                                             tc::AckermannDriveResult* result) {
  tc::AckermannDriveInput input;
  input.speed = speed;
  input.steering_angle = steering;
  *result = processor_->setAckermann(input, t);
  return processor_->update(t);
}

}  // namespace tianracer_sim
