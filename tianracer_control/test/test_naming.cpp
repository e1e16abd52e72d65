#include <string>
#include <vector>

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
// cameraName + imageTopicName): (namespace, name, resolved).
TEST(ResolveTopic, JoinsRelativeNamesKeepsAbsoluteOnesCollapsesSlashes) {
  struct Case {
    std::string ns, name, resolved;
  };
  const std::vector<Case> cases = {
      {"rrbot/camera1", "image_raw", "/rrbot/camera1/image_raw"},  // relative: joined
      {"/rrbot/", "camera1/camera_info", "/rrbot/camera1/camera_info"},
      {"", "scan", "/scan"},
      {"tianracer", "/clock", "/clock"},  // absolute: kept
      {"", "/", "/"},
      {"a//b/", "c/", "/a/b/c"},  // double and trailing slashes collapse
      {"", "", "/"},
  };
  for (const Case& c : cases)
    EXPECT_EQ(resolveTopic(c.ns, c.name), c.resolved) << "'" << c.ns << "', '" << c.name << "'";
}

}  // namespace tianracer_control
