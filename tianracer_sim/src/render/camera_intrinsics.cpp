#include "tianracer_sim/render/camera_intrinsics.h"

#include <cmath>

namespace tianracer_sim {

CameraIntrinsics CameraIntrinsics::fromHorizontalFov(int width, int height, double hfov,
                                                     double near_clip, double far_clip) {
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fx = k.fy = width / (2.0 * std::tan(hfov / 2.0));
  k.cx = (width - 1) / 2.0;
  k.cy = (height - 1) / 2.0;
  k.near_clip = near_clip;
  k.far_clip = far_clip;
  return k;
}

Eigen::Isometry3d opticalFromLinkRotation() {
  // Columns: the optical axes in the link frame. x_O = -y_L, y_O = -z_L, z_O = x_L.
  Eigen::Matrix3d R;
  R << 0, 0, 1,
      -1, 0, 0,
      0, -1, 0;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  return X;
}

}  // namespace tianracer_sim
