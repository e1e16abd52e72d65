// Gazebo camera and depth camera configuration: the <camera> element of a
// <sensor type="camera|depth"> and the libgazebo_ros_camera / libgazebo_ros_openni_kinect
// plugin parameters, parsed and validated, and the CameraInfo gazebo_ros publishes. ROS-free.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_CAMERA_CONFIG_H
#define TIANRACER_SIM_PLUGINS_CAMERA_CAMERA_CONFIG_H

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/render/camera_intrinsics.h"
#include "tianracer_sim/plugins/camera/lens_distortion.h"
#include "tianracer_sim/plugins/camera/wide_angle_lens.h"

namespace tianracer_sim {

/// A camera sensor's configuration is invalid. The message names the sensor, the element and
/// the value, placed at the <sensor>'s line of its model file (e.g. "car.urdf:12: camera sensor
/// 'camera1' on link 'camera': <image><width> 0 out of range 1..8192").
using CameraError = InputError;

/// <image><format>: R8G8B8 (alias RGB_INT8) -> rgb8, B8G8R8 (BGR_INT8) -> bgr8, L8 (L_INT8) ->
/// mono8, L16 (L_INT16) -> mono16, R16G16B16 (RGB_INT16) -> rgb16, BAYER_RGGB8 / BGGR8 / GBRG8 /
/// GRBG8 -> bayer_rggb8 / ... (gazebo_ros_camera_utils.cpp Init, the encoding and step it
/// sets). Mono images are the Rec. 601 luma of the rendered colour,
/// Y = 0.299 R + 0.587 G + 0.114 B (what cv_bridge/OpenCV use for rgb8 -> mono8): mono8 =
/// round(Y) of the 8-bit channels, mono16 = round(Y * 65535 / 255) (full range, 255 -> 65535,
/// little-endian). rgb16 is each rendered 8-bit channel times 257 (full range, little-endian:
/// 8 bits of precision in 16). A Bayer image keeps, at each pixel, the one channel its
/// pattern names there (the pattern's first row starts at the top-left pixel).
enum class ImageFormat {
  kR8G8B8, kB8G8R8, kL8, kL16, kR16G16B16,
  kBayerRGGB8, kBayerBGGR8, kBayerGBRG8, kBayerGRBG8
};

/// sensor_msgs/image_encodings name of a format ("rgb8", "bgr8", "mono8", "mono16", "rgb16",
/// "bayer_rggb8", ...).
const char* imageEncoding(ImageFormat format);
/// Bytes per pixel of a format (3, 3, 1, 2, 6, 1).
int bytesPerPixel(ImageFormat format);
/// Channels per pixel (3 for colour, 1 for mono and Bayer) and bytes per channel (1 or 2).
int channelCount(ImageFormat format);
int bytesPerChannel(ImageFormat format);
/// Channel index (0 R, 1 G, 2 B) that a Bayer format keeps at pixel (row, col); -1 otherwise.
int bayerChannel(ImageFormat format, int row, int col);

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
  /// <sensor type="wideanglecamera">: rendered through a cube map and its <lens>
  /// (wide_angle_lens.h); horizontal_fov may then be up to 2 pi.
  bool wide_angle = false;
  WideAngleLens lens;

  // libgazebo_ros_camera (and the shared part of openni_kinect)
  bool has_plugin = false;  // without one, Gazebo renders but publishes nothing
  std::string plugin_filename;
  /// libgazebo_ros_triggered_camera: one image (and camera_info) per std_msgs/Empty on
  /// <robotNamespace>/<cameraName>/<triggerTopicName>, none without
  /// (gazebo_ros_triggered_camera.cpp); the sensor rate does not apply.
  bool triggered = false;
  std::string trigger_topic = "image_trigger";  // triggerTopicName
  std::string robot_namespace;
  /// <robotNamespace/> given but empty: gazebo_ros's GetRobotNamespace (gazebo_ros_utils.h,
  /// used by gazebo_ros_camera_utils) makes it the model's name; applyModelNamespace() does.
  bool namespace_from_model = false;
  std::string camera_name;           // topics live under <robotNamespace>/<cameraName>/
  std::string image_topic = "image_raw";
  std::string camera_info_topic = "camera_info";
  std::string frame_name;            // default: the sensor's link (Gazebo: "/world")
  double plugin_update_rate = 0.0;   // updateRate; 0 = the sensor rate
  double hack_baseline = 0.0;        // P[3] = -f * hackBaseline
  /// D = [k1 k2 t1 t2 k3]: the plugin's distortionK1.. (gazebo_ros_camera_utils), or with
  /// <autoDistortion> true the <distortion> element's k1 k2 p1 p2 k3.
  double k1 = 0, k2 = 0, k3 = 0, t1 = 0, t2 = 0;
  bool auto_distortion = false;  // plugin <autoDistortion>
  bool border_crop = true;       // plugin <borderCrop>: the crop of barrel distortion
  /// <camera><distortion>, applied to the rendered images (lens_distortion.h); its crop is
  /// k1 < 0 and borderCrop.
  LensDistortion distortion;
  double cx_override = 0.0, cy_override = 0.0, focal_length_override = 0.0;  // Cx, Cy, focalLength

  /// The rate images are published at: updateRate, or the sensor rate when it is 0.
  double publishRate() const { return plugin_update_rate > 0.0 ? plugin_update_rate : update_rate; }
  /// f = W / (2 tan(hfov / 2)).
  double focalLength() const;
  /// Intrinsics for rendering: exactly the published K (makeCameraInfo), read with 0-based
  /// pixel indices: f both axes (focalLength or the plugin's focalLength), principal point
  /// (cx, cy) = K's (Gazebo's (W+1)/2, (H+1)/2 unless Cx/Cy are given), and the clip planes.
  /// Gazebo renders its images centred at ((W-1)/2, (H-1)/2), one pixel off its own K; we
  /// render where K says.
  CameraIntrinsics intrinsics() const;
  /// frameName already is an optical frame at the camera (usesOwnOpticalFrame(),
  /// plugins/camera/optical_frame.h): images are stamped in it and no frame is added.
  bool frame_is_optical = false;
  std::string opticalFrame() const {
    return frame_is_optical ? frame_name : opticalFrameId(frame_name);
  }
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

/// Gives an empty <robotNamespace/> the model's name (CameraConfig::namespace_from_model);
/// a no-op otherwise.
void applyModelNamespace(CameraConfig* config, const std::string& model_name);

/// sensor_msgs/CameraInfo as gazebo_ros fills it, frame = the optical frame:
/// f = W / (2 tan(hfov/2)), cx = (W+1)/2, cy = (H+1)/2 (gazebo_ros's values, kept so that
/// users' calibrations stay valid; the images are rendered with this K, see intrinsics()),
/// K = [f 0 cx; 0 f cy; 0 0 1], R = I, P = [f 0 cx -f*hackBaseline; 0 f cy 0; 0 0 1 0],
/// D = [k1 k2 t1 t2 k3] (plumb_bob).
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

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_CAMERA_CONFIG_H
