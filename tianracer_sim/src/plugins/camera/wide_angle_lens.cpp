#include "tianracer_sim/plugins/camera/wide_angle_lens.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tianracer_sim {

std::optional<WideAngleLens> WideAngleLens::ofType(const std::string& type) {
  // CameraLens::SetType's table: c1, c2, c3, f, fun.
  struct Row {
    const char* name;
    double c1, c2, c3, f;
    Fun fun;
  };
  static const Row kTypes[] = {{"gnomonical", 1, 1, 0, 1, Fun::kTan},
                               {"stereographic", 2, 2, 0, 1, Fun::kTan},
                               {"equidistant", 1, 1, 0, 1, Fun::kId},
                               {"equisolid_angle", 2, 2, 0, 1, Fun::kSin},
                               {"orthographic", 1, 1, 0, 1, Fun::kSin}};
  for (const Row& row : kTypes) {
    if (type != row.name) continue;
    WideAngleLens lens;
    lens.type = type;
    lens.c1 = row.c1;
    lens.c2 = row.c2;
    lens.c3 = row.c3;
    lens.f = row.f;
    lens.fun = row.fun;
    return lens;
  }
  return std::nullopt;
}

std::optional<WideAngleLens::Fun> WideAngleLens::funOf(const std::string& name) {
  if (name == "sin") return Fun::kSin;
  if (name == "tan") return Fun::kTan;
  if (name == "id") return Fun::kId;
  return std::nullopt;
}

double WideAngleLens::apply(double x) const {
  switch (fun) {
    case Fun::kSin: return std::sin(x);
    case Fun::kTan: return std::tan(x);
    case Fun::kId: return x;
  }
  return x;
}

double WideAngleLens::inverse(double y) const {
  switch (fun) {
    case Fun::kSin:
      return std::fabs(y) <= 1.0 ? std::asin(y) : std::numeric_limits<double>::quiet_NaN();
    case Fun::kTan: return std::atan(y);
    case Fun::kId: return y;
  }
  return y;
}

double WideAngleLens::focal(double hfov) const {
  return scale_to_hfov ? 1.0 / (c1 * apply(hfov / 2.0 / c2 + c3)) : f;
}

double WideAngleLens::radius(double theta, double hfov) const {
  return c1 * focal(hfov) * apply(theta / c2 + c3);
}

double WideAngleLens::theta(double r, double hfov) const {
  return (inverse(r / (c1 * focal(hfov))) - c3) * c2;
}

Eigen::Quaterniond cubeFaceRotation(int face) {
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ(), y = Eigen::Vector3d::UnitY();
  switch (face) {
    case 0: return Eigen::Quaterniond::Identity();                    // forward
    case 1: return Eigen::Quaterniond(Eigen::AngleAxisd(M_PI, z));      // back
    case 2: return Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, z));  // left
    case 3: return Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2, z)); // right
    case 4: return Eigen::Quaterniond(Eigen::AngleAxisd(-M_PI / 2, y)); // up
    default: return Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, y)); // down
  }
}

WideAngleMap::WideAngleMap(const WideAngleLens& lens, double hfov, int width, int height)
    : lens_(lens), hfov_(hfov), width_(width), height_(height), n_(lens.env_texture_size) {
  std::array<Eigen::Matrix3d, kCubeFaces> R_CF;  // face frame -> camera frame
  for (int i = 0; i < kCubeFaces; ++i) R_CF[i] = cubeFaceRotation(i).toRotationMatrix();
  // The faces' pinhole: N x N, 90 degrees, centred (camera_intrinsics.h).
  const double fn = n_ / 2.0, cn = (n_ - 1) / 2.0;
  const double cut = lens_.cutRadius(hfov_);
  entries_.resize(static_cast<std::size_t>(width) * height);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      Entry& e = entries_[static_cast<std::size_t>(v) * width + u];
      double r = 0.0;
      const Eigen::Vector3d d = direction(u, v, &r);
      if (d.isZero()) continue;  // no angle for this radius: black
      // wide_lens_map_fp.glsl: rgb *= 1 - smoothstep(cut - 0.02, cut, r).
      const double t = std::clamp((r - (cut - 0.02)) / 0.02, 0.0, 1.0);
      const double keep = 1.0 - t * t * (3.0 - 2.0 * t);
      if (!(keep > 0.0)) continue;
      int face = 0;
      double best = -2.0;
      Eigen::Vector3d df;
      for (int i = 0; i < kCubeFaces; ++i) {
        const Eigen::Vector3d di = R_CF[i].transpose() * d;
        if (di.x() > best) best = di.x(), face = i, df = di;
      }
      // Link-frame pinhole: u = cx - f y / x, v = cy - f z / x.
      const double fu = std::clamp(cn - fn * df.y() / df.x(), 0.0, n_ - 1.0);
      const double fv = std::clamp(cn - fn * df.z() / df.x(), 0.0, n_ - 1.0);
      const int u0 = std::min(static_cast<int>(fu), n_ - 1), v0 = std::min(static_cast<int>(fv), n_ - 1);
      const int u1 = std::min(u0 + 1, n_ - 1), v1 = std::min(v0 + 1, n_ - 1);
      const double au = fu - u0, av = fv - v0;
      const std::size_t base = static_cast<std::size_t>(face) * n_ * n_;
      const auto at = [&](int x, int y) {
        return static_cast<uint32_t>(3 * (base + static_cast<std::size_t>(y) * n_ + x));
      };
      e.texel = {at(u0, v0), at(u1, v0), at(u0, v1), at(u1, v1)};
      e.weight = {static_cast<float>(keep * (1 - au) * (1 - av)), static_cast<float>(keep * au * (1 - av)),
                  static_cast<float>(keep * (1 - au) * av), static_cast<float>(keep * au * av)};
    }
  }
}

Eigen::Vector3d WideAngleMap::direction(int u, int v, double* r_out) const {
  const double x = 2.0 * (u + 0.5) / width_ - 1.0;
  const double y = (1.0 - 2.0 * (v + 0.5) / height_) * height_ / width_;
  const double r = std::hypot(x, y);
  if (r_out) *r_out = r;
  const double theta = lens_.theta(r, hfov_);
  if (!std::isfinite(theta)) return Eigen::Vector3d::Zero();
  if (r == 0.0) return Eigen::Vector3d::UnitX();
  // The shader's map(theta), in the link frame: forward cos(theta), the image's right is -y,
  // its up is +z.
  const double s = std::sin(theta);
  return Eigen::Vector3d(std::cos(theta), -s * x / r, s * y / r);
}

bool WideAngleMap::project(const Eigen::Vector3d& d, double* u, double* v) const {
  const double lateral = std::hypot(d.y(), d.z());
  const double theta = std::atan2(lateral, d.x());
  const double r = lens_.radius(theta, hfov_);
  if (!std::isfinite(r)) return false;
  const double x = lateral > 0.0 ? r * -d.y() / lateral : 0.0;
  const double y = lateral > 0.0 ? r * d.z() / lateral : 0.0;
  *u = (x + 1.0) * width_ / 2.0 - 0.5;
  *v = height_ / 2.0 - y * width_ / 2.0 - 0.5;
  return true;
}

void WideAngleMap::apply(const uint8_t* faces, uint8_t* out) const {
  const std::size_t n = entries_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Entry& e = entries_[i];
    for (int c = 0; c < 3; ++c) {
      const float value = e.weight[0] * faces[e.texel[0] + c] + e.weight[1] * faces[e.texel[1] + c] +
                          e.weight[2] * faces[e.texel[2] + c] + e.weight[3] * faces[e.texel[3] + c];
      out[3 * i + c] = static_cast<uint8_t>(std::min(255.0f, value + 0.5f));
    }
  }
}

}  // namespace tianracer_sim
