#include <gtest/gtest.h>

#include "tianracer_control/frames.h"

namespace tianracer_control {

TEST(ResolveFrame, NoPrefixKeepsTheFrame) {
  EXPECT_EQ(resolveFrame("", "base_link"), "base_link");
  EXPECT_EQ(resolveFrame("/", "odom"), "odom");
}

TEST(ResolveFrame, PrefixIsJoinedWithOneSlash) {
  EXPECT_EQ(resolveFrame("tianracer_02", "base_link"), "tianracer_02/base_link");
  EXPECT_EQ(resolveFrame("/tianracer_02/", "odom"), "tianracer_02/odom");
  EXPECT_EQ(resolveFrame("fleet/car_3", "lidar"), "fleet/car_3/lidar");
}

TEST(ResolveFrame, AbsoluteFrameKeepsNoPrefix) {
  EXPECT_EQ(resolveFrame("tianracer_02", "/world"), "world");
  EXPECT_EQ(resolveFrame("", "/map"), "map");
}

}  // namespace tianracer_control
