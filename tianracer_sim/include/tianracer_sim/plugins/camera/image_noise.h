// Gazebo's per-pixel gaussian image noise, deterministic and fast. ROS-free.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_IMAGE_NOISE_H
#define TIANRACER_SIM_PLUGINS_CAMERA_IMAGE_NOISE_H

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace tianracer_sim {

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

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_IMAGE_NOISE_H
