// fitWheel: which mesh is a wheel about an axle, and its radius, width and centre.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tianracer_assets/wheel_fit.h"

namespace tianracer_assets {
namespace {

TEST(WheelFit, CylinderMeshAboutTheAxis) {
  std::vector<Eigen::Vector3d> v;
  for (int i = 0; i < 32; ++i) {
    const double a = 2 * M_PI * i / 32;
    for (double y : {-0.01, 0.015}) v.emplace_back(0.03 * std::cos(a), y, 0.03 * std::sin(a));
  }
  const WheelFit f = fitWheel(v, Eigen::Vector3d::UnitY());
  EXPECT_TRUE(f.is_wheel);
  EXPECT_NEAR(f.radius, 0.03, 1e-12);
  EXPECT_NEAR(f.width, 0.025, 1e-12);
  EXPECT_TRUE(f.center.isApprox(Eigen::Vector3d(0, 0.0025, 0)));
  // The same points about x are not round.
  EXPECT_FALSE(fitWheel(v, Eigen::Vector3d::UnitX()).is_wheel);
}

}  // namespace
}  // namespace tianracer_assets
