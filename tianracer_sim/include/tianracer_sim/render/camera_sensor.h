// Gazebo camera and depth camera sensors: their configuration (the <camera> element of a
// <sensor type="camera|depth"> and the libgazebo_ros_camera / libgazebo_ros_openni_kinect
// plugin parameters), the CameraInfo gazebo_ros publishes, and the per-frame products (rgb8
// image with Gazebo's per-pixel noise, 32FC1 depth, organized XYZRGB cloud) in buffers that
// are reused frame after frame. ROS-free: message conversion is in ros/camera_msgs.h.
#ifndef TIANRACER_SIM_RENDER_CAMERA_SENSOR_H
#define TIANRACER_SIM_RENDER_CAMERA_SENSOR_H

#include <array>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/render/renderer.h"

namespace tianracer_sim {

/// A camera sensor's configuration is invalid. The message names the sensor, the element and
/// the value (e.g. "camera sensor 'camera1' (line 12): <image><width> 0 out of range 1..8192").
class CameraError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ImageFormat { kR8G8B8, kL8 };

/// The optical frame published for `frame_name` (by TF, rotated rpy(-pi/2, 0, -pi/2) from
/// it) and written in every image, cloud and camera_info header: "<frame_name>_optical_frame",
/// the suffix of the openni/realsense drivers ("camera" -> "camera_optical_frame").
std::string opticalFrameId(const std::string& frame_name);

/// <camera> of a camera or depth sensor plus the libgazebo_ros_camera parameters (the
/// openni_kinect plugin shares them). Defaults are SDF's and gazebo_ros's.
struct CameraConfig {
  std::string name;  // <sensor name>
  std::string type;  // "camera" or "depth"
  std::string link;  // the link the sensor is attached to
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  // sensor pose in the link frame
  double update_rate = 0.0;  // <update_rate> of the sensor, Hz (0 = every step, as Gazebo)
  int line = 0;

  // <camera>
  double horizontal_fov = 1.047;  // rad, in (0, pi)
  int width = 320;                // 1..8192
  int height = 240;
  ImageFormat format = ImageFormat::kR8G8B8;
  std::string format_name = "R8G8B8";
  double near_clip = 0.1;  // > 0
  double far_clip = 100.0;  // > near
  bool noise = false;      // <noise><type>gaussian
  double noise_mean = 0.0;   // [0, 1] colour units
  double noise_stddev = 0.0;
  uint32_t noise_seed = 0;  // 0: derived from the sensor name (runs are repeatable)

  // libgazebo_ros_camera (and the shared part of openni_kinect)
  bool has_plugin = false;  // without one, Gazebo renders but publishes nothing
  std::string plugin_filename;
  std::string robot_namespace;
  std::string camera_name;           // topics live under <robotNamespace>/<cameraName>/
  std::string image_topic = "image_raw";
  std::string camera_info_topic = "camera_info";
  std::string frame_name;            // default: the sensor's link (Gazebo: "/world")
  double plugin_update_rate = 0.0;   // updateRate; 0 = the sensor rate
  double hack_baseline = 0.0;        // P[3] = -f * hackBaseline
  double k1 = 0, k2 = 0, k3 = 0, t1 = 0, t2 = 0;  // reported in D only, images are not distorted
  double cx_override = 0.0, cy_override = 0.0, focal_length_override = 0.0;  // Cx, Cy, focalLength

  /// The rate images are published at: updateRate, or the sensor rate when it is 0.
  double publishRate() const { return plugin_update_rate > 0.0 ? plugin_update_rate : update_rate; }
  /// f = W / (2 tan(hfov / 2)).
  double focalLength() const;
  /// Intrinsics for rendering: f both axes, centred ((W-1)/2, (H-1)/2), the clip planes.
  CameraIntrinsics intrinsics() const;
  std::string opticalFrame() const { return opticalFrameId(frame_name); }
  /// Pose of the optical frame in the link frame: X_LS * rpy(-pi/2, 0, -pi/2).
  Eigen::Isometry3d X_LO() const;
};

/// A "depth" sensor with libgazebo_ros_openni_kinect (or libgazebo_ros_depth_camera).
struct DepthCameraConfig {
  CameraConfig camera;  // image_topic defaults to "ir/image_raw", camera_info to "ir/camera_info"
  std::string depth_image_topic = "depth/image_raw";
  std::string depth_camera_info_topic = "depth/camera_info";
  std::string point_cloud_topic = "points";
  double baseline = 0.0;               // <baseline>: read, unused (as in gazebo_ros)
  double point_cloud_cutoff = 0.4;     // depth and cloud are NaN at or below this (m)
  double point_cloud_cutoff_max = 5.0; // ... and at or beyond this
};

/// Parses and validates a camera sensor (type "camera"). Throws CameraError. Unknown elements
/// of <camera> and unknown plugin parameters are reported once to `warn`.
CameraConfig parseCameraConfig(const SensorSpec& sensor, const WarningSink& warn = {});
/// The same for type "depth" (also accepts "camera" sensors with an openni plugin).
DepthCameraConfig parseDepthCameraConfig(const SensorSpec& sensor, const WarningSink& warn = {});

/// sensor_msgs/CameraInfo as gazebo_ros fills it (SPEC §5.2), frame = the optical frame:
/// f = W / (2 tan(hfov/2)), cx = (W+1)/2, cy = (H+1)/2 (gazebo_ros's values; the rendered
/// principal point is at (W-1)/2, (H-1)/2 in 0-based pixels, i.e. cx - 1), K = [f 0 cx; 0 f cy;
/// 0 0 1], R = I, P = [f 0 cx -f*hackBaseline; 0 f cy 0; 0 0 1 0], D = [k1 k2 t1 t2 k3] (plumb_bob).
struct CameraInfo {
  std::string frame_id;
  int width = 0;
  int height = 0;
  std::string distortion_model = "plumb_bob";
  std::array<double, 5> D{};
  std::array<double, 9> K{};
  std::array<double, 9> R{};
  std::array<double, 12> P{};
};
CameraInfo makeCameraInfo(const CameraConfig& config);

/// Gazebo's gaussian image noise: one sample per pixel, added to each of its channels in
/// [0, 1] units, then clamped. Samples come from a 64 Ki-entry table of the quantiles of
/// N(mean, stddev) (rounded to 1/255 steps), indexed by 16-bit words of SplitMix64 hashes of
/// (frame seed, pixel); the frame seeds are drawn from a std::mt19937 seeded by `seed`. Exact
/// marginal distribution, deterministic, a few ns a pixel.
class ImageNoise {
 public:
  ImageNoise() = default;
  ImageNoise(double mean, double stddev, uint32_t seed);
  bool enabled() const { return enabled_; }
  /// Adds noise to `pixels` pixels of `channels` bytes each.
  void apply(uint8_t* data, std::size_t pixels, int channels);

 private:
  bool enabled_ = false;
  std::vector<int16_t> table_;
  std::vector<uint16_t> saturating_;  // table_ as (max(n, 0) | max(-n, 0) << 8), each <= 255
  std::mt19937 rng_;
};

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

  /// Renders the view of the sensor on link pose X_WL (X_WC = X_WL * X_LS), applies noise.
  void render(const Scene& scene, const Eigen::Isometry3d& X_WL);

  const CameraConfig& config() const { return config_; }
  const CameraInfo& info() const { return info_; }
  /// W*H*channels() bytes, rows top to bottom.
  const std::vector<uint8_t>& image() const { return image_; }
  int channels() const { return config_.format == ImageFormat::kL8 ? 1 : 3; }
  uint64_t renderCount() const { return renders_; }

 private:
  CameraConfig config_;
  Renderer* renderer_;
  CameraInfo info_;
  CameraIntrinsics intrinsics_;
  ImageNoise noise_;
  std::vector<uint8_t> image_;
  std::vector<uint8_t> rgb_scratch_;  // L8 only
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
  const std::vector<uint8_t>& image() const { return image_; }  // rgb8 (or mono8 for L8)
  int channels() const { return config_.camera.format == ImageFormat::kL8 ? 1 : 3; }
  /// W*H metres along the optical axis, NaN outside (cutoff, cutoffMax).
  const std::vector<float>& depth() const { return depth_; }
  /// H*W*CloudLayout::kPointStep bytes: x = d (u - (W-1)/2) / f, y = d (v - (H-1)/2) / f,
  /// z = d, NaN where the depth is NaN; rgb from the (noisy) image.
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
  std::vector<float> ray_x_, ray_y_;  // (u - (W-1)/2) / f and (v - (H-1)/2) / f
  bool cloud_dense_ = false;
  uint64_t renders_ = 0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_RENDER_CAMERA_SENSOR_H
