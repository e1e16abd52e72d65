// Gazebo camera and depth camera sensors: the per-frame products (image with Gazebo's
// per-pixel noise, 32FC1 depth, organized XYZRGB cloud) in buffers that are reused frame after
// frame. Their configuration and CameraInfo are in camera_config.h, the noise in
// image_noise.h (both included: this header declares the whole camera API). ROS-free: message
// conversion is in ros/camera_msgs.h.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_CAMERA_SENSOR_H
#define TIANRACER_SIM_PLUGINS_CAMERA_CAMERA_SENSOR_H

#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/plugins/camera/camera_config.h"
#include "tianracer_sim/plugins/camera/image_noise.h"
#include "tianracer_sim/plugins/camera/lens_distortion.h"
#include "tianracer_sim/plugins/camera/wide_angle_lens.h"
#include "tianracer_sim/render/renderer.h"

namespace tianracer_sim {

/// Byte layout of the organized cloud (PCL's PointXYZRGB): x, y, z, rgb as FLOAT32 at offsets
/// 0, 4, 8, 16; 32 bytes a point; rgb is a float whose bits are 0x00RRGGBB.
struct CloudLayout {
  static constexpr int kOffsetX = 0;
  static constexpr int kOffsetY = 4;
  static constexpr int kOffsetZ = 8;
  static constexpr int kOffsetRgb = 16;
  static constexpr int kPointStep = 32;
};

/// A camera: renders through a shared Renderer into its own reused image buffer.
class CameraSensor {
 public:
  CameraSensor(CameraConfig config, Renderer& renderer);

  /// Renders the view of the sensor on link pose X_WL (X_WC = X_WL * X_LS), applies noise. A
  /// wideanglecamera renders its six cube faces and maps them through its lens.
  void render(const Scene& scene, const Eigen::Isometry3d& X_WL);

  const CameraConfig& config() const { return config_; }
  const CameraInfo& info() const { return info_; }
  /// W*H*bytesPerPixel() bytes, rows top to bottom, in the configured format (encoding()).
  const std::vector<uint8_t>& image() const { return image_; }
  int channels() const { return channelCount(config_.format); }
  int bytesPerPixel() const { return tianracer_sim::bytesPerPixel(config_.format); }
  const char* encoding() const { return imageEncoding(config_.format); }
  uint64_t renderCount() const { return renders_; }

 private:
  CameraConfig config_;
  Renderer* renderer_;
  CameraInfo info_;
  CameraIntrinsics intrinsics_;
  ImageNoise noise_;
  DistortionMap distortion_;          // empty without <distortion>
  std::vector<uint8_t> undistorted_;  // the rendered image, before the lens
  WideAngleMap wide_angle_;           // wideanglecamera: cube map -> image
  std::vector<uint8_t> cube_faces_;   // its six N x N views
  std::vector<uint8_t> image_;
  std::vector<uint8_t> rgb_scratch_;  // formats other than R8G8B8
  uint64_t renders_ = 0;
};

/// What a depth camera frame should produce (skip what nobody subscribes to).
struct DepthOutputs {
  bool image = true;
  bool depth = true;
  bool cloud = true;
};

/// A depth camera (openni_kinect): colour and depth from one render pass, then the depth image
/// (NaN outside (cutoff, cutoffMax)) and the organized cloud in the optical frame.
class DepthCameraSensor {
 public:
  DepthCameraSensor(DepthCameraConfig config, Renderer& renderer);

  void render(const Scene& scene, const Eigen::Isometry3d& X_WL, DepthOutputs outputs = {});

  const DepthCameraConfig& config() const { return config_; }
  const CameraInfo& info() const { return info_; }  // both camera_infos carry this
  /// The colour image in the configured format, as CameraSensor::image().
  const std::vector<uint8_t>& image() const { return image_; }
  int channels() const { return channelCount(config_.camera.format); }
  int bytesPerPixel() const { return tianracer_sim::bytesPerPixel(config_.camera.format); }
  const char* encoding() const { return imageEncoding(config_.camera.format); }
  /// W*H metres along the optical axis, NaN outside (cutoff, cutoffMax).
  const std::vector<float>& depth() const { return depth_; }
  /// H*W*CloudLayout::kPointStep bytes, built with the published K (0-based pixel indices
  /// u, v): x = d (u - cx) / fx, y = d (v - cy) / fy, z = d, NaN where the depth is NaN; rgb
  /// from the (noisy) image (grey for mono formats).
  const std::vector<uint8_t>& cloud() const { return cloud_; }
  /// False when any cloud point is NaN.
  bool cloudIsDense() const { return cloud_dense_; }
  /// Writes the cloud of the last render (rendered with image and depth) to `out`:
  /// H*W*CloudLayout::kPointStep bytes, padding zero, the bytes cloud() holds after a render
  /// with outputs.cloud. For callers that build it straight into their own buffer.
  void writeCloud(uint8_t* out) const;
  uint64_t renderCount() const { return renders_; }

 private:
  DepthCameraConfig config_;
  Renderer* renderer_;
  CameraInfo info_;
  CameraIntrinsics intrinsics_;
  ImageNoise noise_;
  std::vector<uint8_t> image_;
  std::vector<uint8_t> rgb_scratch_;
  std::vector<float> depth_;
  std::vector<uint8_t> cloud_;
  std::vector<float> ray_x_, ray_y_;  // (u - cx) / fx and (v - cy) / fy of the published K
  bool cloud_dense_ = false;
  uint64_t renders_ = 0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_CAMERA_SENSOR_H
