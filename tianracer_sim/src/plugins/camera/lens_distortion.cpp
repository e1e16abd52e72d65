// Lens distortion (lens_distortion.h). Gazebo builds its map by scattering: every texel of an
// undistorted grid is distorted and written where it lands, holes filled from their neighbours
// (gazebo-classic gazebo/rendering/Distortion.cc SetCamera); we invert the same model exactly
// for every output pixel instead, so the map has no holes and no texel rounding.
#include "tianracer_sim/plugins/camera/lens_distortion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/LU>

namespace tianracer_sim {

Eigen::Vector2d distortNormalized(const LensDistortion& d, const Eigen::Vector2d& x) {
  const double r2 = x.squaredNorm();
  const double radial = 1.0 + d.k1 * r2 + d.k2 * r2 * r2 + d.k3 * r2 * r2 * r2;
  return {x.x() * radial + 2.0 * d.p1 * x.x() * x.y() + d.p2 * (r2 + 2.0 * x.x() * x.x()),
          x.y() * radial + d.p1 * (r2 + 2.0 * x.y() * x.y()) + 2.0 * d.p2 * x.x() * x.y()};
}

namespace {

Eigen::Matrix2d jacobian(const LensDistortion& d, const Eigen::Vector2d& x) {
  const double r2 = x.squaredNorm();
  const double radial = 1.0 + d.k1 * r2 + d.k2 * r2 * r2 + d.k3 * r2 * r2 * r2;
  const double dradial = d.k1 + 2.0 * d.k2 * r2 + 3.0 * d.k3 * r2 * r2;  // d radial / d r2
  const double X = x.x(), Y = x.y();
  Eigen::Matrix2d J;
  J(0, 0) = radial + X * dradial * 2.0 * X + 2.0 * d.p1 * Y + d.p2 * (2.0 * X + 4.0 * X);
  J(0, 1) = X * dradial * 2.0 * Y + 2.0 * d.p1 * X + d.p2 * 2.0 * Y;
  J(1, 0) = Y * dradial * 2.0 * X + d.p1 * 2.0 * X + 2.0 * d.p2 * Y;
  J(1, 1) = radial + Y * dradial * 2.0 * Y + d.p1 * (2.0 * Y + 4.0 * Y) + 2.0 * d.p2 * X;
  return J;
}

}  // namespace

bool undistortNormalized(const LensDistortion& d, const Eigen::Vector2d& x_d, Eigen::Vector2d* x) {
  Eigen::Vector2d p = x_d;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector2d f = distortNormalized(d, p) - x_d;
    if (f.norm() < 1e-12) break;
    const Eigen::Matrix2d J = jacobian(d, p);
    const double det = J.determinant();
    if (!(std::fabs(det) > 1e-12)) return false;
    Eigen::Vector2d step = J.inverse() * f;
    // Damped: never jump more than the distance from the centre (stays on the inner branch).
    const double limit = 0.5 * std::max(p.norm(), 1e-3);
    if (step.norm() > limit) step *= limit / step.norm();
    p -= step;
    if (!p.allFinite()) return false;
  }
  // A solution where the map folds over (det <= 0) is not on the one-to-one branch.
  if ((distortNormalized(d, p) - x_d).norm() > 1e-9 || jacobian(d, p).determinant() <= 0.0)
    return false;
  *x = p;
  return true;
}

DistortionMap::DistortionMap(const LensDistortion& d, const CameraIntrinsics& k)
    : width_(k.width), height_(k.height) {
  const double f = k.fx;
  const double cdx = k.cx + (d.center_x - 0.5) * k.width;
  const double cdy = k.cy + (d.center_y - 0.5) * k.height;
  if (d.crop && d.k1 < 0.0) {
    // The distorted frame's corners (pixel edges), as Distortion.cc distorts (0,0) and (1,1).
    const Eigen::Vector2d a =
        distortNormalized(d, {(-0.5 - cdx) / f, (-0.5 - cdy) / f}) * f;
    const Eigen::Vector2d b =
        distortNormalized(d, {(k.width - 0.5 - cdx) / f, (k.height - 0.5 - cdy) / f}) * f;
    const Eigen::Vector2d s((b.x() - a.x()) / k.width, (b.y() - a.y()) / k.height);
    if (s.x() > 1e-7 && s.y() > 1e-7) scale_ = s;  // Gazebo keeps 1 for a degenerate scale
  }
  const float nan = std::numeric_limits<float>::quiet_NaN();
  src_.assign(static_cast<std::size_t>(width_) * height_, Eigen::Vector2f(nan, nan));
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      const Eigen::Vector2d x_d(scale_.x() * (u - cdx) / f, scale_.y() * (v - cdy) / f);
      Eigen::Vector2d x;
      if (!undistortNormalized(d, x_d, &x)) continue;
      const double su = cdx + f * x.x(), sv = cdy + f * x.y();
      if (su < -0.5 || sv < -0.5 || su > width_ - 0.5 || sv > height_ - 0.5) continue;
      src_[static_cast<std::size_t>(v) * width_ + u] =
          Eigen::Vector2f(static_cast<float>(su), static_cast<float>(sv));
    }
  }
}

void DistortionMap::apply(const std::uint8_t* src, std::uint8_t* dst, int channels) const {
  const std::size_t row = static_cast<std::size_t>(width_) * channels;
  for (int v = 0; v < height_; ++v) {
    for (int u = 0; u < width_; ++u) {
      std::uint8_t* out = dst + v * row + static_cast<std::size_t>(u) * channels;
      const Eigen::Vector2f s = source(u, v);
      if (!(s.x() == s.x())) {  // NaN: black
        for (int c = 0; c < channels; ++c) out[c] = 0;
        continue;
      }
      // Bilinear between the four nearest pixel centres, clamped at the border.
      const float fx = std::min(std::max(s.x(), 0.0f), static_cast<float>(width_ - 1));
      const float fy = std::min(std::max(s.y(), 0.0f), static_cast<float>(height_ - 1));
      const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
      const int x1 = std::min(x0 + 1, width_ - 1), y1 = std::min(y0 + 1, height_ - 1);
      const float ax = fx - x0, ay = fy - y0;
      const std::uint8_t* p00 = src + y0 * row + static_cast<std::size_t>(x0) * channels;
      const std::uint8_t* p01 = src + y0 * row + static_cast<std::size_t>(x1) * channels;
      const std::uint8_t* p10 = src + y1 * row + static_cast<std::size_t>(x0) * channels;
      const std::uint8_t* p11 = src + y1 * row + static_cast<std::size_t>(x1) * channels;
      for (int c = 0; c < channels; ++c) {
        const float top = p00[c] + ax * (p01[c] - p00[c]);
        const float bottom = p10[c] + ax * (p11[c] - p10[c]);
        out[c] = static_cast<std::uint8_t>(top + ay * (bottom - top) + 0.5f);
      }
    }
  }
}

}  // namespace tianracer_sim
