// Gazebo's wide-angle camera (<sensor type="wideanglecamera">, gazebo/rendering/WideAngleCamera.cc
// and media/materials/programs/wide_lens_map_fp.glsl): the scene is rendered into a cube map of
// six 90-degree views, and each output pixel looks up the direction its lens function gives it.
// The lens (SDF <camera><lens>) and the per-pixel lookup table, computed once. ROS-free, no GL.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_WIDE_ANGLE_LENS_H
#define TIANRACER_SIM_PLUGINS_CAMERA_WIDE_ANGLE_LENS_H

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace tianracer_sim {

/// <lens>: r = c1 f fun(theta / c2 + c3), r the distance from the image centre in units of
/// half the image width, theta the angle from the optical axis (camera.sdf's custom_function).
struct WideAngleLens {
  enum class Fun { kSin, kTan, kId };
  std::string type = "stereographic";  // SDF's default
  double c1 = 2.0, c2 = 2.0, c3 = 0.0, f = 1.0;
  Fun fun = Fun::kTan;
  bool scale_to_hfov = true;       // f such that theta = hfov/2 lands at the image's side edge
  double cutoff_angle = 1.5707;    // rad; beyond it the image is black
  int env_texture_size = 256;      // cube map face size, pixels

  /// The named types' constants (CameraLens::SetType): gnomonical (1, 1, 0, 1, tan),
  /// stereographic (2, 2, 0, 1, tan), equidistant (1, 1, 0, 1, id), equisolid_angle
  /// (2, 2, 0, 1, sin), orthographic (1, 1, 0, 1, sin). nullopt for any other name (custom too).
  static std::optional<WideAngleLens> ofType(const std::string& type);
  /// "sin", "tan", "id" (CameraLensPrivate::MapFunctionEnum); nullopt otherwise.
  static std::optional<Fun> funOf(const std::string& name);

  double apply(double x) const;    // fun(x)
  double inverse(double y) const;  // asin, atan or y; NaN outside asin's domain
  /// The f used: 1 / (c1 fun(hfov/2 / c2 + c3)) with scale_to_hfov (CameraLens::
  /// SetUniformVariables), else <f>.
  double focal(double hfov) const;
  /// Radius of a ray at angle theta: c1 f fun(theta / c2 + c3).
  double radius(double theta, double hfov) const;
  /// Angle of a radius (the shader): (inverse(r / (c1 f)) - c3) c2; NaN where undefined.
  double theta(double r, double hfov) const;
  /// The shader's cut: radius(cutoff_angle); pixels at r >= it are black, and the colour fades
  /// over [cut - 0.02, cut] (smoothstep, as wide_lens_map_fp.glsl).
  double cutRadius(double hfov) const { return radius(cutoff_angle, hfov); }
};

/// The cube map's faces: the views of the camera link frame (x forward, y left, z up) rotated
/// to look forward, back, left, right, up and down; each a square 90-degree pinhole image.
constexpr int kCubeFaces = 6;
/// Rotation of face i's camera frame in the wide-angle camera's frame.
Eigen::Quaterniond cubeFaceRotation(int face);

/// Output pixel -> cube map lookup for one lens and image size, made once: per pixel the face,
/// the four texels around the direction (bilinear) and the cut-off's factor.
class WideAngleMap {
 public:
  WideAngleMap() = default;
  WideAngleMap(const WideAngleLens& lens, double hfov, int width, int height);

  /// The direction (unit, camera link frame) output pixel (u, v) looks along, and its radius;
  /// theta NaN gives a zero vector. Pixel centres (u + 0.5, v + 0.5) in the shader's
  /// coordinates: x = (2 (u + 0.5) / W - 1), y = (1 - 2 (v + 0.5) / H) H / W, r = |(x, y)|.
  Eigen::Vector3d direction(int u, int v, double* r = nullptr) const;
  /// The pixel (u, v), continuous with centres at integers, that a direction lands on; false
  /// when it lands nowhere on the image plane's model (theta beyond the lens's range).
  bool project(const Eigen::Vector3d& d, double* u, double* v) const;

  /// Writes the W*H*3 output from the six faces (each N*N*3 rgb, rows top to bottom, in
  /// cubeFaceRotation's order, contiguous).
  void apply(const uint8_t* faces, uint8_t* out) const;

  int faceSize() const { return n_; }
  bool empty() const { return entries_.empty(); }

 private:
  struct Entry {
    std::array<uint32_t, 4> texel{};  // byte offsets into faces
    std::array<float, 4> weight{};    // bilinear weights times the cut-off's factor
  };
  WideAngleLens lens_;
  double hfov_ = 0.0;
  int width_ = 0, height_ = 0, n_ = 0;
  std::vector<Entry> entries_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_WIDE_ANGLE_LENS_H
