// libgazebo_ros_bumper on a contact sensor: configuration, topics, and the contact states
// grouped by pair and expressed in the output frame.
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/plugins/bumper/bumper.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

SensorSpec contactSpec(const std::string& plugin) {
  const RobotExtensions ext = parseExtensions(
      "<robot name='r'><link name='base'/><gazebo reference='base'>"
      "<sensor type='contact' name='bumper'><update_rate>50</update_rate>"
      "<contact><collision>base_collision</collision></contact>" +
          plugin + "</sensor></gazebo></robot>",
      "test.urdf", {});
  return ext.links.at("base").sensors.at(0);
}

TEST(SensorsBumper, ConfigAndTopics) {
  const SensorSpec spec = contactSpec(
      "<plugin name='b' filename='libgazebo_ros_bumper.so'><robotNamespace>/car</robotNamespace>"
      "<bumperTopicName>bumper</bumperTopicName><frameName>base</frameName></plugin>");
  EXPECT_EQ(test::kindOf(spec), "bumper");
  const BumperConfig c = parseBumperConfig(spec, "car");
  EXPECT_EQ(c.link, "base");
  EXPECT_EQ(c.topic(), "/car/bumper");
  EXPECT_EQ(c.frame_name, "base");
  EXPECT_DOUBLE_EQ(c.update_rate, 50.0);
  const auto topics = sensorTopics(spec, "car");
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].topic, "/car/bumper");
  EXPECT_EQ(topics[0].msg_type, "gazebo_msgs/ContactsState");
  EXPECT_DOUBLE_EQ(topics[0].rate, 50.0);

  // gazebo_ros_bumper's defaults: bumper_states in the world frame, no namespace.
  const BumperConfig d =
      parseBumperConfig(contactSpec("<plugin name='b' filename='libgazebo_ros_bumper.so'/>"), "car");
  EXPECT_EQ(d.topic(), "/bumper_states");
  EXPECT_EQ(d.frame_name, "world");

  // Without the plugin Gazebo publishes nothing.
  EXPECT_TRUE(sensorTopics(contactSpec(""), "car").empty());
}

TEST(SensorsBumper, BadInput) {
  std::vector<std::string> warnings;
  parseBumperConfig(contactSpec("<plugin name='b' filename='libgazebo_ros_bumper.so'>"
                                "<bumperTopic>x</bumperTopic></plugin>"),
                    "car", [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("<bumperTopic> is not a parameter of libgazebo_ros_bumper"));
  EXPECT_THAT(warnings[0], HasSubstr("contact sensor 'bumper' of model 'car'"));
  try {
    parseBumperConfig(contactSpec("<plugin name='b' filename='libgazebo_ros_bumper.so'>"
                                  "<bumperTopicName> </bumperTopicName></plugin>"),
                      "car");
    FAIL() << "an empty topic must be refused";
  } catch (const SensorError& e) {
    EXPECT_THAT(e.what(), HasSubstr("<bumperTopicName> is empty"));
  }
}

TEST(SensorsBumper, StatesByPairInTheOutputFrame) {
  std::vector<BumperContact> contacts(3);
  contacts[0] = {"car::base", "wall::link", {1.0, 0.0, 0.1}, {-1.0, 0.0, 0.0}, 0.002, 0.01};
  contacts[1] = {"car::base", "box::link", {0.0, 1.0, 0.1}, {0.0, -1.0, 0.0}, 0.001, 0.002};
  contacts[2] = {"car::base", "wall::link", {1.0, 0.2, 0.1}, {-1.0, 0.0, 0.0}, 0.003, 0.03};
  std::vector<BumperState> states;
  bumperStates(contacts, Eigen::Isometry3d::Identity(), 0.001, &states);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_EQ(states[0].collision1, "car::base");
  EXPECT_EQ(states[0].collision2, "wall::link");
  ASSERT_EQ(states[0].positions.size(), 2u);
  EXPECT_EQ(states[0].depths, (std::vector<double>{0.002, 0.003}));
  // f = J / dt along the normal: 10 N and 30 N pushing the car back (-x).
  EXPECT_NEAR(states[0].forces[0].x(), -10.0, 1e-9);
  EXPECT_NEAR(states[0].total_force.x(), -40.0, 1e-9);
  EXPECT_NEAR(states[0].total_force.norm(), 40.0, 1e-9);
  EXPECT_EQ(states[1].collision2, "box::link");
  EXPECT_NEAR(states[1].total_force.y(), -2.0, 1e-9);

  // In a link frame F at (1, 0, 0) turned 90 degrees about z: p_F = R^T (p_W - p_WF).
  Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
  X_WF.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X_WF.translation() = Eigen::Vector3d(1.0, 0.0, 0.0);
  bumperStates(contacts, X_WF, 0.001, &states);
  EXPECT_TRUE(states[0].positions[1].isApprox(Eigen::Vector3d(0.2, 0.0, 0.1), 1e-12));
  EXPECT_TRUE(states[0].normals[0].isApprox(Eigen::Vector3d(0.0, 1.0, 0.0), 1e-12));
  EXPECT_TRUE(states[0].total_force.isApprox(Eigen::Vector3d(0.0, 40.0, 0.0), 1e-12));

  bumperStates({}, Eigen::Isometry3d::Identity(), 0.001, &states);
  EXPECT_TRUE(states.empty());
}

}  // namespace
}  // namespace tianracer_sim
