// libgazebo_ros_p3d: configuration, the reading in the world and relative to a link, offsets,
// noise, and link velocities from poses.
#include <cmath>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/plugins/p3d/p3d.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

SensorSpec p3dSpec(const std::string& params) {
  const RobotExtensions ext = parseExtensions(
      "<robot name='r'><link name='base'/><gazebo><plugin name='gt' filename='libgazebo_ros_p3d.so'>" +
          params + "</plugin></gazebo></robot>",
      "test.urdf", {});
  return modelPluginSensor(ext.model_plugins.at(0));
}

Eigen::Isometry3d pose(double x, double y, double yaw) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(x, y, 0.1);
  return X;
}

TEST(SensorsP3d, ConfigAndTopics) {
  const SensorSpec spec = p3dSpec(
      "<robotNamespace>/car</robotNamespace><bodyName>base</bodyName><topicName>ground_truth</topicName>"
      "<updateRate>30</updateRate><gaussianNoise>0.01</gaussianNoise><xyzOffsets>1 0 0</xyzOffsets>");
  EXPECT_EQ(test::kindOf(spec), "p3d");
  const P3dConfig c = parseP3dConfig(spec, "car");
  EXPECT_EQ(c.topic(), "/car/ground_truth");
  EXPECT_EQ(c.frame_name, "world");
  EXPECT_TRUE(c.reference_link.empty());
  EXPECT_DOUBLE_EQ(c.update_rate, 30.0);
  EXPECT_EQ(c.xyz_offsets, Eigen::Vector3d(1, 0, 0));
  const auto topics = sensorTopics(spec, "car");
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].msg_type, "nav_msgs/Odometry");
  EXPECT_EQ(parseP3dConfig(p3dSpec("<bodyName>base</bodyName><topicName>t</topicName>"
                                   "<frameName>/map</frameName>"), "car").reference_link, "");
  EXPECT_EQ(parseP3dConfig(p3dSpec("<bodyName>base</bodyName><topicName>t</topicName>"
                                   "<frameName>chassis</frameName>"), "car").reference_link,
            "chassis");
}

TEST(SensorsP3d, BadInput) {
  const auto error = [](const std::string& params) {
    try {
      parseP3dConfig(p3dSpec(params), "car");
    } catch (const SensorError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_THAT(error("<topicName>t</topicName>"), HasSubstr("p3d plugin 'gt' of model 'car': <bodyName> is missing"));
  EXPECT_THAT(error("<bodyName>base</bodyName>"), HasSubstr("<topicName> is missing"));
  EXPECT_THAT(error("<bodyName>base</bodyName><topicName>t</topicName><updateRate>-2</updateRate>"),
              HasSubstr("<updateRate> -2 must be >= 0"));
  EXPECT_THAT(error("<bodyName>base</bodyName><topicName>t</topicName><updateRate>nan</updateRate>"),
              HasSubstr("<updateRate> nan is not finite"));
}

TEST(SensorsP3d, WorldFrameReading) {
  P3dConfig c;
  c.link = "base";
  c.topic_name = "t";
  P3dSensor p3d(c);
  LinkState s;
  s.X_WL = pose(1, 2, 0.5);
  s.v_W = Eigen::Vector3d(0.3, 0.1, 0);
  s.w_W = Eigen::Vector3d(0, 0, 0.2);
  const P3dReading& r = p3d.measure(s, nullptr);
  EXPECT_TRUE(r.position.isApprox(Eigen::Vector3d(1, 2, 0.1)));
  EXPECT_NEAR(r.orientation.angularDistance(Eigen::Quaterniond(s.X_WL.linear())), 0.0, 1e-12);
  EXPECT_EQ(r.linear, s.v_W);  // world frame, p3d's convention
  EXPECT_EQ(r.angular, s.w_W);
  EXPECT_EQ(r.variance, 0.0);
}

TEST(SensorsP3d, RelativeToALinkWithOffsets) {
  P3dConfig c;
  c.link = "base";
  c.topic_name = "t";
  c.reference_link = "ref";
  c.xyz_offsets = Eigen::Vector3d(0, 0, 1);
  c.rpy_offsets = Eigen::Vector3d(0, 0, 0.1);
  P3dSensor p3d(c);
  LinkState body, ref;
  body.X_WL = pose(2, 1, 0.7);
  body.v_W = Eigen::Vector3d(1, 0, 0);
  ref.X_WL = pose(1, 1, M_PI / 2);
  ref.v_W = Eigen::Vector3d(0, 0.5, 0);
  const P3dReading& r = p3d.measure(body, &ref);
  // Body is 1 m along world x from ref, i.e. along ref's -y; z offset 1 m added.
  EXPECT_TRUE(r.position.isApprox(Eigen::Vector3d(0, -1, 1), 1e-12));
  const double yaw = 2 * std::atan2(r.orientation.z(), r.orientation.w());
  EXPECT_NEAR(yaw, 0.7 - M_PI / 2 + 0.1, 1e-12);
  EXPECT_TRUE(r.linear.isApprox(Eigen::Vector3d(-0.5, -1, 0), 1e-12));
}

TEST(SensorsP3d, NoiseStatistics) {
  P3dConfig c;
  c.link = "base";
  c.topic_name = "t";
  c.gaussian_noise = 0.05;
  P3dSensor p3d(c);
  LinkState s;
  double sum = 0, sum2 = 0;
  constexpr int kN = 10000;
  for (int i = 0; i < kN; ++i) {
    const double x = p3d.measure(s, nullptr).linear.y();
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / kN, sd = std::sqrt(sum2 / kN - mean * mean);
  EXPECT_NEAR(mean, 0.0, 0.005);
  EXPECT_NEAR(sd, 0.05, 0.005);
  EXPECT_DOUBLE_EQ(p3d.measure(s, nullptr).variance, 0.0025);
  EXPECT_TRUE(p3d.measure(s, nullptr).position.isZero());  // the pose carries no noise
}

TEST(SensorsP3d, LinkMotionFromPoses) {
  LinkMotion m;
  const double w = 0.8, v = 0.5, dt = 0.001;
  LinkState s;
  for (int k = 0; k <= 100; ++k) {
    const double t = k * dt;
    s = m.record(t, pose(v * t, 0, w * t));
  }
  EXPECT_NEAR(s.v_W.x(), v, 1e-9);
  EXPECT_NEAR(s.w_W.z(), w, 1e-9);
  m.reset();
  EXPECT_TRUE(m.record(1.0, pose(3, 3, 0)).v_W.isZero());  // no history: at rest
}

}  // namespace
}  // namespace tianracer_sim
