#include "tianracer_assets/wheel_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tianracer_assets {

WheelFit fitWheel(const std::vector<Eigen::Vector3d>& vertices_B, const Eigen::Vector3d& axis_B) {
  WheelFit fit;
  if (vertices_B.size() < 6 || !(axis_B.norm() > 0.0)) return fit;
  const Eigen::Vector3d a = axis_B.normalized();
  double amin = std::numeric_limits<double>::infinity(), amax = -amin, rmax = 0.0;
  for (const auto& v : vertices_B) {
    const double s = v.dot(a);
    amin = std::min(amin, s);
    amax = std::max(amax, s);
    rmax = std::max(rmax, (v - s * a).norm());
  }
  if (!(rmax > 0.0)) return fit;
  // Outer vertices must go all the way round the axis: 12 sectors of 30 degrees.
  const Eigen::Vector3d e1 = a.unitOrthogonal(), e2 = a.cross(e1);
  constexpr int kSectors = 12;
  double sector_r[kSectors] = {0};
  for (const auto& v : vertices_B) {
    const Eigen::Vector3d r = v - v.dot(a) * a;
    const double ang = std::atan2(r.dot(e2), r.dot(e1));
    int k = static_cast<int>(std::floor((ang + M_PI) / (2.0 * M_PI) * kSectors));
    k = std::min(std::max(k, 0), kSectors - 1);
    sector_r[k] = std::max(sector_r[k], r.norm());
  }
  fit.roundness = *std::min_element(sector_r, sector_r + kSectors) / rmax;
  fit.radius = rmax;
  fit.width = amax - amin;
  fit.center = 0.5 * (amin + amax) * a;
  fit.is_wheel = fit.roundness > 0.98 && fit.width > 0.0;
  return fit;
}

}  // namespace tianracer_assets
