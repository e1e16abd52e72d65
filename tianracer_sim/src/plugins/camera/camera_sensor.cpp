#include "tianracer_sim/plugins/camera/camera_sensor.h"

#include <cstring>
#include <limits>

namespace tianracer_sim {

namespace {

void toMono(const std::vector<uint8_t>& rgb, std::vector<uint8_t>* mono) {
  // ITU-R BT.601 luma, in integers.
  const std::size_t n = mono->size();
  for (std::size_t i = 0; i < n; ++i) {
    const uint8_t* p = &rgb[3 * i];
    (*mono)[i] = static_cast<uint8_t>((299 * p[0] + 587 * p[1] + 114 * p[2] + 500) / 1000);
  }
}

// The same luma on the 16-bit scale: round(Y * 65535 / 255) = round(Y * 257), little-endian.
void toMono16(const std::vector<uint8_t>& rgb, std::vector<uint8_t>* mono) {
  const std::size_t n = mono->size() / 2;
  for (std::size_t i = 0; i < n; ++i) {
    const uint8_t* p = &rgb[3 * i];
    const uint32_t y = (257u * (299u * p[0] + 587u * p[1] + 114u * p[2]) + 500u) / 1000u;
    (*mono)[2 * i] = static_cast<uint8_t>(y & 0xff);
    (*mono)[2 * i + 1] = static_cast<uint8_t>(y >> 8);
  }
}

void toBgr(const std::vector<uint8_t>& rgb, std::vector<uint8_t>* bgr) {
  const std::size_t n = bgr->size() / 3;
  for (std::size_t i = 0; i < n; ++i) {
    (*bgr)[3 * i] = rgb[3 * i + 2];
    (*bgr)[3 * i + 1] = rgb[3 * i + 1];
    (*bgr)[3 * i + 2] = rgb[3 * i];
  }
}

// rgb16: each 8-bit channel v as the 16-bit v * 257 = (v << 8) | v, little-endian.
void toRgb16(const std::vector<uint8_t>& rgb, std::vector<uint8_t>* out) {
  const std::size_t n = rgb.size();
  for (std::size_t i = 0; i < n; ++i) {
    (*out)[2 * i] = rgb[i];
    (*out)[2 * i + 1] = rgb[i];
  }
}

// Bayer: at each pixel the one channel the pattern names there.
void toBayer(ImageFormat format, const std::vector<uint8_t>& rgb, int width,
             std::vector<uint8_t>* out) {
  const std::size_t n = out->size();
  const int even[2] = {bayerChannel(format, 0, 0), bayerChannel(format, 0, 1)};
  const int odd[2] = {bayerChannel(format, 1, 0), bayerChannel(format, 1, 1)};
  for (std::size_t i = 0; i < n; ++i) {
    const int row = static_cast<int>(i / width), col = static_cast<int>(i % width);
    const int* channel = (row & 1) ? odd : even;
    (*out)[i] = rgb[3 * i + channel[col & 1]];
  }
}

// Turns the rendered rgb8 `rgb` into `out` in `format` and applies the noise. rgb8 renders
// straight into `out` (rgb == out). Mono8 takes its noise after the conversion (one sample a
// pixel on the grey value); the other formats take it on the colour, one sample a pixel
// added to every channel, before the byte order or scale changes.
void finishImage(ImageFormat format, int width, std::vector<uint8_t>* rgb,
                 std::vector<uint8_t>* out, ImageNoise* noise, std::size_t pixels) {
  switch (format) {
    case ImageFormat::kR8G8B8:
      noise->apply(out->data(), pixels, 3);
      break;
    case ImageFormat::kL8:
      toMono(*rgb, out);
      noise->apply(out->data(), pixels, 1);
      break;
    case ImageFormat::kB8G8R8:
      noise->apply(rgb->data(), pixels, 3);
      toBgr(*rgb, out);
      break;
    case ImageFormat::kL16:
      noise->apply(rgb->data(), pixels, 3);
      toMono16(*rgb, out);
      break;
    case ImageFormat::kR16G16B16:
      noise->apply(rgb->data(), pixels, 3);
      toRgb16(*rgb, out);
      break;
    case ImageFormat::kBayerRGGB8:
    case ImageFormat::kBayerBGGR8:
    case ImageFormat::kBayerGBRG8:
    case ImageFormat::kBayerGRBG8:
      noise->apply(rgb->data(), pixels, 3);
      toBayer(format, *rgb, width, out);
      break;
  }
}

}  // namespace

CameraSensor::CameraSensor(CameraConfig config, Renderer& renderer)
    : config_(std::move(config)),
      renderer_(&renderer),
      info_(makeCameraInfo(config_)),
      intrinsics_(config_.intrinsics()),
      noise_(config_.noise ? ImageNoise(config_.noise_mean, config_.noise_stddev, config_.noise_seed)
                           : ImageNoise()) {
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  image_.resize(pixels * bytesPerPixel());
  if (config_.format != ImageFormat::kR8G8B8) rgb_scratch_.resize(pixels * 3);
  if (config_.distortion.enabled()) {
    distortion_ = DistortionMap(config_.distortion, intrinsics_);
    undistorted_.resize(pixels * 3);
  }
  if (config_.wide_angle) {
    wide_angle_ = WideAngleMap(config_.lens, config_.horizontal_fov, config_.width, config_.height);
    const std::size_t n = static_cast<std::size_t>(wide_angle_.faceSize());
    cube_faces_.resize(kCubeFaces * n * n * 3);
  }
}

void CameraSensor::render(const Scene& scene, const Eigen::Isometry3d& X_WL) {
  const Eigen::Isometry3d X_WC = X_WL * config_.X_LS;
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  const bool direct = config_.format == ImageFormat::kR8G8B8;
  uint8_t* rgb = direct ? image_.data() : rgb_scratch_.data();
  if (!wide_angle_.empty()) {
    // WideAngleCamera: six 90-degree square views (its env cameras), then each pixel's lookup.
    const int n = wide_angle_.faceSize();
    CameraIntrinsics face;
    face.width = face.height = n;
    face.fx = face.fy = n / 2.0;
    face.cx = face.cy = (n - 1) / 2.0;
    face.near_clip = config_.near_clip;
    face.far_clip = config_.far_clip;
    const std::size_t face_bytes = static_cast<std::size_t>(n) * n * 3;
    for (int i = 0; i < kCubeFaces; ++i) {
      Eigen::Isometry3d X_WF = X_WC;
      X_WF.linear() = X_WC.linear() * cubeFaceRotation(i).toRotationMatrix();
      renderer_->renderView(scene, X_WF, face, cube_faces_.data() + i * face_bytes, nullptr);
    }
    wide_angle_.apply(cube_faces_.data(), rgb);
  } else if (distortion_.empty()) {
    renderer_->renderView(scene, X_WC, intrinsics_, rgb, nullptr);
  } else {
    // The lens distorts the rendered image before the noise (per output pixel) is added.
    renderer_->renderView(scene, X_WC, intrinsics_, undistorted_.data(), nullptr);
    distortion_.apply(undistorted_.data(), rgb, 3);
  }
  finishImage(config_.format, config_.width, &rgb_scratch_, &image_, &noise_, pixels);
  ++renders_;
}

DepthCameraSensor::DepthCameraSensor(DepthCameraConfig config, Renderer& renderer)
    : config_(std::move(config)),
      renderer_(&renderer),
      info_(makeCameraInfo(config_.camera)),
      intrinsics_(config_.camera.intrinsics()),
      noise_(config_.camera.noise ? ImageNoise(config_.camera.noise_mean, config_.camera.noise_stddev,
                                               config_.camera.noise_seed)
                                  : ImageNoise()) {
  const CameraConfig& c = config_.camera;
  const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
  image_.resize(pixels * bytesPerPixel());
  if (c.format != ImageFormat::kR8G8B8) rgb_scratch_.resize(pixels * 3);
  depth_.resize(pixels);
  cloud_.assign(pixels * CloudLayout::kPointStep, 0);
  // The published K, so that the cloud is what depth_image_proc makes of depth + camera_info.
  const double fx = info_.K[0], fy = info_.K[4], cx = info_.K[2], cy = info_.K[5];
  ray_x_.resize(c.width);
  ray_y_.resize(c.height);
  for (int u = 0; u < c.width; ++u) ray_x_[u] = static_cast<float>((u - cx) / fx);
  for (int v = 0; v < c.height; ++v) ray_y_[v] = static_cast<float>((v - cy) / fy);
}

void DepthCameraSensor::render(const Scene& scene, const Eigen::Isometry3d& X_WL,
                               DepthOutputs outputs) {
  const CameraConfig& c = config_.camera;
  const Eigen::Isometry3d X_WC = X_WL * c.X_LS;
  const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
  const bool want_rgb = outputs.image || outputs.cloud;
  const bool want_depth = outputs.depth || outputs.cloud;
  if (!want_rgb && !want_depth) return;
  const bool direct = c.format == ImageFormat::kR8G8B8;
  uint8_t* rgb = want_rgb ? (direct ? image_.data() : rgb_scratch_.data()) : nullptr;
  renderer_->renderView(scene, X_WC, intrinsics_, rgb, want_depth ? depth_.data() : nullptr);
  ++renders_;
  if (want_rgb) finishImage(c.format, c.width, &rgb_scratch_, &image_, &noise_, pixels);
  if (!want_depth) return;

  const float lo = static_cast<float>(config_.point_cloud_cutoff);
  const float hi = static_cast<float>(config_.point_cloud_cutoff_max);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  bool dense = true;
  for (std::size_t i = 0; i < pixels; ++i) {
    const float d = depth_[i];
    if (!(d > lo && d < hi)) {
      depth_[i] = nan;
      dense = false;
    }
  }
  cloud_dense_ = dense;
  if (!outputs.cloud) return;
  writeCloud(cloud_.data());
}

void DepthCameraSensor::writeCloud(uint8_t* out) const {
  const CameraConfig& c = config_.camera;
  const int bpp = bytesPerPixel();
  // Byte offsets of r, g, b in a pixel (mono: the grey value, its high byte for mono16).
  int ro = 0, go = 0, bo = 0;
  switch (c.format) {
    case ImageFormat::kR8G8B8: ro = 0, go = 1, bo = 2; break;
    case ImageFormat::kB8G8R8: ro = 2, go = 1, bo = 0; break;
    case ImageFormat::kL8: break;
    case ImageFormat::kL16: ro = go = bo = 1; break;
    case ImageFormat::kR16G16B16: ro = 1, go = 3, bo = 5; break;  // the high bytes
    default: break;  // Bayer: the pixel's one value, as grey
  }
  for (int v = 0; v < c.height; ++v) {
    const float ry = ray_y_[v];
    for (int u = 0; u < c.width; ++u, out += CloudLayout::kPointStep) {
      const std::size_t i = static_cast<std::size_t>(v) * c.width + u;
      const float d = depth_[i];
      const uint8_t* px = &image_[i * bpp];
      const uint32_t r = px[ro], g = px[go], b = px[bo];
      // x, y, z, 0 | rgb (PCL: 0x00RRGGBB in a float's bits), 0, 0, 0; NaN depth stays NaN.
      float xyz0[4] = {d * ray_x_[u], d * ry, d, 0.0f};
      const uint32_t rgb0[4] = {(r << 16) | (g << 8) | b, 0, 0, 0};
      std::memcpy(out + CloudLayout::kOffsetX, xyz0, sizeof(xyz0));
      std::memcpy(out + CloudLayout::kOffsetRgb, rgb0, sizeof(rgb0));
    }
  }
}

}  // namespace tianracer_sim
