#include "tianracer_sim/render/camera_sensor.h"

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

}  // namespace

CameraSensor::CameraSensor(CameraConfig config, Renderer& renderer)
    : config_(std::move(config)),
      renderer_(&renderer),
      info_(makeCameraInfo(config_)),
      intrinsics_(config_.intrinsics()),
      noise_(config_.noise ? ImageNoise(config_.noise_mean, config_.noise_stddev, config_.noise_seed)
                           : ImageNoise()) {
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  image_.resize(pixels * channels());
  if (config_.format == ImageFormat::kL8) rgb_scratch_.resize(pixels * 3);
}

void CameraSensor::render(const Scene& scene, const Eigen::Isometry3d& X_WL) {
  const Eigen::Isometry3d X_WC = X_WL * config_.X_LS;
  const std::size_t pixels = static_cast<std::size_t>(config_.width) * config_.height;
  if (config_.format == ImageFormat::kL8) {
    renderer_->renderView(scene, X_WC, intrinsics_, rgb_scratch_.data(), nullptr);
    toMono(rgb_scratch_, &image_);
  } else {
    renderer_->renderView(scene, X_WC, intrinsics_, image_.data(), nullptr);
  }
  noise_.apply(image_.data(), pixels, channels());
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
  image_.resize(pixels * channels());
  if (c.format == ImageFormat::kL8) rgb_scratch_.resize(pixels * 3);
  depth_.resize(pixels);
  cloud_.assign(pixels * CloudLayout::kPointStep, 0);
  const double f = c.focalLength();
  ray_x_.resize(c.width);
  ray_y_.resize(c.height);
  for (int u = 0; u < c.width; ++u) ray_x_[u] = static_cast<float>((u - 0.5 * (c.width - 1)) / f);
  for (int v = 0; v < c.height; ++v) ray_y_[v] = static_cast<float>((v - 0.5 * (c.height - 1)) / f);
}

void DepthCameraSensor::render(const Scene& scene, const Eigen::Isometry3d& X_WL,
                               DepthOutputs outputs) {
  const CameraConfig& c = config_.camera;
  const Eigen::Isometry3d X_WC = X_WL * c.X_LS;
  const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
  const bool want_rgb = outputs.image || outputs.cloud;
  const bool want_depth = outputs.depth || outputs.cloud;
  if (!want_rgb && !want_depth) return;
  const bool mono = c.format == ImageFormat::kL8;
  uint8_t* rgb = want_rgb ? (mono ? rgb_scratch_.data() : image_.data()) : nullptr;
  renderer_->renderView(scene, X_WC, intrinsics_, rgb, want_depth ? depth_.data() : nullptr);
  ++renders_;
  if (want_rgb) {
    if (mono) toMono(rgb_scratch_, &image_);
    noise_.apply(image_.data(), pixels, channels());
  }
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
  const int ch = channels();
  for (int v = 0; v < c.height; ++v) {
    const float ry = ray_y_[v];
    for (int u = 0; u < c.width; ++u, out += CloudLayout::kPointStep) {
      const std::size_t i = static_cast<std::size_t>(v) * c.width + u;
      const float d = depth_[i];
      const uint8_t* px = &image_[i * ch];
      const uint32_t r = px[0], g = px[ch > 1 ? 1 : 0], b = px[ch > 1 ? 2 : 0];
      // x, y, z, 0 | rgb (PCL: 0x00RRGGBB in a float's bits), 0, 0, 0; NaN depth stays NaN.
      float xyz0[4] = {d * ray_x_[u], d * ry, d, 0.0f};
      const uint32_t rgb0[4] = {(r << 16) | (g << 8) | b, 0, 0, 0};
      std::memcpy(out + CloudLayout::kOffsetX, xyz0, sizeof(xyz0));
      std::memcpy(out + CloudLayout::kOffsetRgb, rgb0, sizeof(rgb0));
    }
  }
}

}  // namespace tianracer_sim
