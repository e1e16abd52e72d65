// Gazebo's camera lens distortion (<camera><distortion>), applied to rendered images as
// gazebo-classic gazebo/rendering/Distortion.cc does: Brown's model distorts where an
// undistorted point appears, the output image shows at each pixel the rendered colour of the
// undistorted point that lands there, black where none does, optionally scaled so that the
// distorted image of the frame fills it (the crop of barrel distortion). ROS-free.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_LENS_DISTORTION_H
#define TIANRACER_SIM_PLUGINS_CAMERA_LENS_DISTORTION_H

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "tianracer_sim/render/camera_intrinsics.h"

namespace tianracer_sim {

/// <distortion>: k1 k2 k3 (radial), p1 p2 (tangential), center (in image fractions, 0.5 0.5
/// = the principal point); crop: scale the distorted image to remove the black border
/// (Gazebo: barrel only, k1 < 0, and gazebo_ros's <borderCrop>, default true).
struct LensDistortion {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;
  double center_x = 0.5, center_y = 0.5;
  bool crop = false;
  /// Gazebo applies nothing when all five coefficients are 0.
  bool enabled() const { return k1 != 0.0 || k2 != 0.0 || k3 != 0.0 || p1 != 0.0 || p2 != 0.0; }
};

/// Brown's model, Distortion::Distort: for x in normalized image coordinates (pixels from the
/// distortion centre over f), r2 = |x|^2,
///   x_d = x (1 + k1 r2 + k2 r2^2 + k3 r2^3) + (2 p1 x y + p2 (r2 + 2 x^2)),
///   y_d = y (1 + k1 r2 + k2 r2^2 + k3 r2^3) + (p1 (r2 + 2 y^2) + 2 p2 x y),
/// OpenCV's plumb_bob with D = [k1 k2 p1 p2 k3] (what camera_info publishes).
Eigen::Vector2d distortNormalized(const LensDistortion& d, const Eigen::Vector2d& x);

/// The undistorted point whose distortion is x_d (Newton's method from x_d, on the branch
/// nearest the centre where the map is still one-to-one); false when there is none.
bool undistortNormalized(const LensDistortion& d, const Eigen::Vector2d& x_d, Eigen::Vector2d* x);

/// For every output pixel, where in the rendered (undistorted) image its colour comes from.
/// Pixel (u, v), 0-based, sits at (u - c_x) / f from the distortion centre
/// c = (cx + (center_x - 0.5) W, cy + (center_y - 0.5) H), cx, cy and f the rendering
/// intrinsics (the published K), so that OpenCV's undistort with K and D gives the undistorted
/// camera's image back. With crop, output pixel u first moves to c_x + (u - c_x) s_x, s the
/// span of the distorted image corners over the image size (Distortion.cc
/// CalculateAndApplyDistortionScale); Gazebo normalizes by the image width where we
/// normalize by f (the same when hfov = 2 atan(1/2)), and scales about the image centre.
class DistortionMap {
 public:
  DistortionMap() = default;
  DistortionMap(const LensDistortion& d, const CameraIntrinsics& k);
  bool empty() const { return src_.empty(); }
  int width() const { return width_; }
  int height() const { return height_; }
  /// The source position of output pixel (u, v) in the rendered image, (NaN, NaN) for black.
  Eigen::Vector2f source(int u, int v) const { return src_[static_cast<std::size_t>(v) * width_ + u]; }
  /// The crop scale (1, 1 without crop).
  Eigen::Vector2d scale() const { return scale_; }
  /// dst(u, v) = src bilinearly sampled at source(u, v), black outside; 8-bit channels.
  void apply(const std::uint8_t* src, std::uint8_t* dst, int channels) const;

 private:
  int width_ = 0, height_ = 0;
  Eigen::Vector2d scale_{1.0, 1.0};
  std::vector<Eigen::Vector2f> src_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_LENS_DISTORTION_H
