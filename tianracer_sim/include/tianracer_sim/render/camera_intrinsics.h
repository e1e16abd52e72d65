// A pinhole camera's intrinsics and the link-to-optical rotation, shared by the renderer and
// the camera sensors. ROS-free, no GL.
#ifndef TIANRACER_SIM_RENDER_CAMERA_INTRINSICS_H
#define TIANRACER_SIM_RENDER_CAMERA_INTRINSICS_H

#include <Eigen/Geometry>

namespace tianracer_sim {

/// A pinhole camera. Pixel (u, v) has its centre at (u, v), u to the right and v down from the
/// top-left pixel; a point (X, Y, Z) of the optical frame (z forward, x right, y down) lands at
/// u = fx X / Z + cx, v = fy Y / Z + cy. A centred camera has cx = (W - 1) / 2, cy = (H - 1) / 2.
struct CameraIntrinsics {
  int width = 0;
  int height = 0;
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  double near_clip = 0.1;
  double far_clip = 100.0;

  /// Gazebo's camera: f = W / (2 tan(hfov / 2)) for both axes, centred.
  static CameraIntrinsics fromHorizontalFov(int width, int height, double hfov, double near_clip,
                                            double far_clip);
};

/// Rotation from a camera link frame (x forward, y left, z up, as Gazebo's cameras) to the
/// optical frame (z forward, x right, y down): rpy(-pi/2, 0, -pi/2).
Eigen::Isometry3d opticalFromLinkRotation();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_RENDER_CAMERA_INTRINSICS_H
