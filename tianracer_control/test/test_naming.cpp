#include <gtest/gtest.h>

#include "tianracer_control/naming.h"

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

// ros::names::resolve's joining, as gazebo_ros plugins name their topics (robotNamespace +
// cameraName + imageTopicName).
TEST(ResolveTopic, RelativeNamesJoinTheNamespace) {
  EXPECT_EQ(resolveTopic("rrbot/camera1", "image_raw"), "/rrbot/camera1/image_raw");
  EXPECT_EQ(resolveTopic("/rrbot/", "camera1/camera_info"), "/rrbot/camera1/camera_info");
  EXPECT_EQ(resolveTopic("", "scan"), "/scan");
}

TEST(ResolveTopic, AbsoluteNamesAreKept) {
  EXPECT_EQ(resolveTopic("tianracer", "/clock"), "/clock");
  EXPECT_EQ(resolveTopic("", "/"), "/");
}

TEST(ResolveTopic, DoubleAndTrailingSlashesCollapse) {
  EXPECT_EQ(resolveTopic("a//b/", "c/"), "/a/b/c");
  EXPECT_EQ(resolveTopic("", ""), "/");
}

}  // namespace tianracer_control
