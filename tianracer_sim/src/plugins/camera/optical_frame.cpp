#include "tianracer_sim/plugins/camera/optical_frame.h"

#include <optional>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/camera/camera_config.h"

namespace tianracer_sim {

bool usesOwnOpticalFrame(const urdf::ModelInterface& model, const std::string& link,
                         const Eigen::Isometry3d& X_LO, const std::string& frame) {
  const std::optional<Eigen::Isometry3d> X_LF = fixedPose(model, link, frame);
  if (!X_LF) return false;
  const Eigen::AngleAxisd turn(X_LF->linear().transpose() * X_LO.linear());
  return turn.angle() < 0.01;
}

bool usesOwnOpticalFrame(const urdf::ModelInterface* model, const CameraConfig& camera) {
  return model && usesOwnOpticalFrame(*model, camera.link, camera.X_LO(), camera.frame_name);
}

}  // namespace tianracer_sim
