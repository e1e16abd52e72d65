// The drive plugins' core (plugins/drives/drives.h) without physics: parameters and defaults as
// gazebo_plugins reads them, bad values, wheel speeds from a twist, the acceleration ramp, the
// encoder and world odometry, the update schedules and planar_move's odometry.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/drives/drives.h"
#include "tianracer_sim/plugins/model_report.h"
#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {
namespace {

SensorSpec plugin(const std::string& filename, const std::map<std::string, std::string>& params) {
  PluginSpec p;
  p.name = "drive";
  p.filename = filename;
  p.params = params;
  return modelPluginSensor(p);
}

bool mentions(const std::vector<std::string>& list, const std::string& text) {
  for (const std::string& s : list)
    if (s.find(text) != std::string::npos) return true;
  return false;
}

TEST(DriveConfig, DiffDriveDefaultsAreUpstreamsAndEachMissingOneIsNoted) {
  std::vector<std::string> warnings;
  const DriveConfig c = parseDriveConfig(plugin("libgazebo_ros_diff_drive.so", {}), "bot",
                                         [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_EQ(c.kind, DriveKind::kDiffDrive);
  EXPECT_EQ(c.commandTopic(), "/bot/cmd_vel");  // GazeboRos: the model's name
  EXPECT_EQ(c.odometryTopic(), "/bot/odom");
  EXPECT_EQ(c.odometry_frame, "odom");
  EXPECT_EQ(c.robot_base_frame, "base_footprint");
  EXPECT_EQ(c.odometry_source, OdomSource::kWorld);
  EXPECT_TRUE(c.publish_odometry);
  EXPECT_TRUE(c.publish_odom_tf);
  EXPECT_FALSE(c.publish_wheel_tf);
  EXPECT_FALSE(c.publish_wheel_joint_state);
  EXPECT_EQ(c.wheel_separation, 0.34);
  EXPECT_EQ(c.wheel_diameter, 0.15);
  EXPECT_EQ(c.wheel_torque, 5.0);
  EXPECT_EQ(c.wheel_acceleration, 0.0);
  EXPECT_EQ(c.update_rate, 100.0);
  EXPECT_EQ(c.joints, (std::vector<std::string>{"left_joint", "right_joint"}));
  EXPECT_EQ(c.pose_covariance[0], 0.00001);
  EXPECT_EQ(c.pose_covariance[14], 1e12);
  EXPECT_EQ(c.pose_covariance[35], 0.001);
  EXPECT_EQ(c.twist_covariance[0], 0.0);
  EXPECT_TRUE(warnings.empty());
  EXPECT_TRUE(mentions(c.defaulted, "missing <wheelSeparation>, defaults to 0.34"));
  EXPECT_TRUE(mentions(c.defaulted, "missing <publishTf>, defaults to true"));
  EXPECT_TRUE(mentions(c.defaulted, "missing <leftJoint>, defaults to \"left_joint\""));
  EXPECT_TRUE(mentions(c.defaulted, "missing <rosDebugLevel>"));
  EXPECT_EQ(c.defaulted.size(), 17u);
}

TEST(DriveConfig, DiffDriveReadsEveryParameter) {
  std::vector<std::string> warnings;
  const DriveConfig c = parseDriveConfig(
      plugin("libgazebo_ros_diff_drive.so",
             {{"robotNamespace", "/r1"}, {"commandTopic", "cmd"}, {"odometryTopic", "/o"},
              {"odometryFrame", "o"}, {"robotBaseFrame", "base_link"}, {"publishWheelTF", "1"},
              {"publishOdomTF", "false"}, {"publishWheelJointState", "TRUE"},
              {"wheelSeparation", "0.5"}, {"wheelDiameter", "0.2"}, {"wheelAcceleration", "1.5"},
              {"wheelTorque", "20"}, {"updateRate", "30"}, {"odometrySource", "encoder"},
              {"leftJoint", "l"}, {"rightJoint", "r"}, {"publishTf", "0"}, {"rosDebugLevel", "Debug"},
              {"legacyMode", "false"}, {"alwaysOn", "true"}, {"wheelRadius", "3"}}),
      "bot", [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_EQ(c.commandTopic(), "/r1/cmd");
  EXPECT_EQ(c.odometryTopic(), "/o");
  EXPECT_EQ(c.jointStatesTopic(), "/r1/joint_states");
  EXPECT_EQ(c.odometry_frame, "o");
  EXPECT_EQ(c.robot_base_frame, "base_link");
  EXPECT_TRUE(c.publish_wheel_tf);
  EXPECT_FALSE(c.publish_odom_tf);
  EXPECT_TRUE(c.publish_wheel_joint_state);
  EXPECT_FALSE(c.publish_odometry);
  EXPECT_EQ(c.wheel_separation, 0.5);
  EXPECT_EQ(c.wheel_diameter, 0.2);
  EXPECT_EQ(c.wheel_acceleration, 1.5);
  EXPECT_EQ(c.wheel_torque, 20.0);
  EXPECT_EQ(c.update_rate, 30.0);
  EXPECT_EQ(c.odometry_source, OdomSource::kEncoder);
  EXPECT_EQ(c.joints, (std::vector<std::string>{"l", "r"}));
  EXPECT_EQ(c.ros_debug_level, "Debug");
  EXPECT_TRUE(c.defaulted.empty());
  // Only the parameter the plugin does not read is reported (legacyMode and alwaysOn: noetic
  // ignores them too).
  ASSERT_EQ(warnings.size(), 1u) << ::testing::PrintToString(warnings);
  EXPECT_NE(warnings[0].find("<wheelRadius> is not a parameter of libgazebo_ros_diff_drive.so"),
            std::string::npos);
  // publishTf off: no odometry topic, only the command.
  const std::vector<SensorTopic> topics = publishedTopics(c);
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].topic, "/r1/joint_states");
  EXPECT_EQ(topics[1].topic, "/r1/cmd");
}

TEST(DriveConfig, AnEmptyRobotNamespaceIsTheModelsName) {
  EXPECT_EQ(parseDriveConfig(plugin("libgazebo_ros_diff_drive.so", {{"robotNamespace", ""}}), "m")
                .commandTopic(),
            "/m/cmd_vel");
  EXPECT_EQ(parseDriveConfig(plugin("libgazebo_ros_diff_drive.so", {{"robotNamespace", "/"}}), "m")
                .commandTopic(),
            "/cmd_vel");
}

TEST(DriveConfig, SkidSteerDefaultsAndCovariances) {
  DriveConfig c = parseDriveConfig(plugin("libgazebo_ros_skid_steer_drive.so", {}), "bot");
  EXPECT_EQ(c.kind, DriveKind::kSkidSteer);
  EXPECT_EQ(c.commandTopic(), "/cmd_vel");  // no model-name default
  EXPECT_FALSE(c.publish_odom_tf);          // broadcastTF defaults to false
  EXPECT_EQ(c.wheel_separation, 0.4);
  EXPECT_EQ(c.wheel_torque, 5.0);
  EXPECT_EQ(c.joints, (std::vector<std::string>{"left_front_joint", "right_front_joint",
                                                "left_rear_joint", "right_rear_joint"}));
  EXPECT_EQ(c.pose_covariance[0], 0.0001);
  EXPECT_EQ(c.twist_covariance[35], 0.01);
  EXPECT_FALSE(mentions(c.defaulted, "broadcastTF"));  // upstream: ROS_INFO, not a warning
  EXPECT_TRUE(mentions(c.defaulted, "missing <torque>, defaults to 5"));
  c = parseDriveConfig(plugin("libgazebo_ros_skid_steer_drive.so",
                              {{"robotNamespace", "s"}, {"broadcastTF", "true"},
                               {"covariance_x", "1"}, {"covariance_y", "2"}, {"covariance_yaw", "3"}}),
                       "bot");
  EXPECT_EQ(c.odometryTopic(), "/s/odom");
  EXPECT_TRUE(c.publish_odom_tf);
  EXPECT_EQ(c.pose_covariance[7], 2.0);
  EXPECT_EQ(c.twist_covariance[35], 3.0);
}

TEST(DriveConfig, PlanarMoveDefaults) {
  const DriveConfig c = parseDriveConfig(plugin("libgazebo_ros_planar_move.so", {}), "box");
  EXPECT_EQ(c.kind, DriveKind::kPlanarMove);
  EXPECT_EQ(c.commandTopic(), "/cmd_vel");
  EXPECT_EQ(c.update_rate, 20.0);  // odometryRate
  EXPECT_EQ(c.cmd_timeout, -1.0);
  EXPECT_TRUE(c.joints.empty());
  EXPECT_TRUE(mentions(c.defaulted, "missing <odometryRate>, defaults to 20"));
  EXPECT_TRUE(mentions(c.defaulted, "missing <cmdTimeout>, defaults to -1"));
}

TEST(DriveConfig, BadValuesNameThePluginElementAndValue) {
  const auto error = [](const std::string& file, const std::map<std::string, std::string>& p) {
    try {
      parseDriveConfig(plugin(file, p), "bot");
    } catch (const SensorError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string diff = "libgazebo_ros_diff_drive.so";
  EXPECT_EQ(error(diff, {{"wheelDiameter", "0"}}),
            "diff_drive plugin 'drive' of model 'bot': <wheelDiameter> 0 must be > 0 (wheel rates "
            "are rim speeds / (wheelDiameter / 2))");
  EXPECT_NE(error(diff, {{"wheelDiameter", "-1"}}).find("<wheelDiameter> -1 must be > 0"),
            std::string::npos);
  EXPECT_NE(error(diff, {{"wheelSeparation", "0"}}).find("<wheelSeparation> 0 must be > 0"),
            std::string::npos);
  EXPECT_NE(error(diff, {{"wheelTorque", "nan"}}).find("<wheelTorque> nan is not finite"),
            std::string::npos);
  EXPECT_NE(error(diff, {{"wheelAcceleration", "-2"}}).find("<wheelAcceleration> -2 must be >= 0"),
            std::string::npos);
  EXPECT_NE(error(diff, {{"updateRate", "fast"}}).find("<updateRate> 'fast' is not a number"),
            std::string::npos);
  EXPECT_NE(error(diff, {{"publishTf", "yes"}}).find("<publishTf> 'yes' is not a boolean"),
            std::string::npos);
  EXPECT_NE(error(diff, {{"leftJoint", ""}}).find("a wheel joint's name is empty"), std::string::npos);
  EXPECT_NE(error("libgazebo_ros_skid_steer_drive.so", {{"torque", "-1"}})
                .find("skid_steer_drive plugin 'drive' of model 'bot': <torque> -1 must be >= 0"),
            std::string::npos);
  EXPECT_NE(error("libgazebo_ros_planar_move.so", {{"odometryRate", "-5"}})
                .find("planar_move plugin 'drive' of model 'bot': <odometryRate> -5 must be >= 0"),
            std::string::npos);
}

TEST(DriveConfig, TheRegistryKnowsTheThreePlugins) {
  for (const char* f : {"libgazebo_ros_diff_drive.so", "libgazebo_ros_skid_steer_drive.so",
                        "libgazebo_ros_planar_move.so"}) {
    const SensorKind* kind = findSensorKind(plugin(f, {}));
    ASSERT_NE(kind, nullptr) << f;
    EXPECT_EQ(kind->id, "drive");
  }
  EXPECT_EQ(findSensorKind(plugin("libgazebo_ros_force.so", {})), nullptr);
  const std::vector<SensorTopic> t = sensorTopics(plugin("libgazebo_ros_diff_drive.so", {}), "bot");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].topic, "/bot/odom");
  EXPECT_EQ(t[0].msg_type, "nav_msgs/Odometry");
  EXPECT_EQ(t[0].rate, 100.0);
}

TEST(DriveMaths, WheelSpeedsFromATwist) {
  const WheelSpeeds s = wheelSpeeds(0.5, 0.5, 0.24);
  EXPECT_DOUBLE_EQ(s.left, 0.44);
  EXPECT_DOUBLE_EQ(s.right, 0.56);
  const WheelSpeeds spin = wheelSpeeds(0.0, -1.0, 0.4);
  EXPECT_DOUBLE_EQ(spin.left, 0.2);
  EXPECT_DOUBLE_EQ(spin.right, -0.2);
}

TEST(DriveMaths, TheAccelerationRampMovesByAtMostAccelTimesDt) {
  WheelSpeeds issued;
  // No limit: the target.
  WheelSpeeds out = rampWheelSpeeds({1.0, 1.0}, {0.0, 0.0}, 0.0, 0.01, &issued);
  EXPECT_EQ(out.left, 1.0);
  EXPECT_EQ(issued.left, 0.0);
  // 2 m/s^2 at 100 Hz: 0.02 m/s per update, as long as the wheels follow.
  WheelSpeeds current;
  for (int k = 1; k <= 10; ++k) {
    out = rampWheelSpeeds({1.0, -1.0}, current, 2.0, 0.01, &issued);
    EXPECT_NEAR(out.left, 0.02 * k, 1e-12);
    EXPECT_NEAR(out.right, -0.02 * k, 1e-12);
    current = out;
  }
  // Within 0.01 m/s of the target on either wheel: the target itself.
  out = rampWheelSpeeds({1.0, -1.0}, {0.995, 0.0}, 2.0, 0.01, &issued);
  EXPECT_EQ(out.left, 1.0);
  EXPECT_EQ(out.right, -1.0);
}

TEST(DriveMaths, EncoderOdometryIntegratesArcs) {
  EncoderOdometry o;
  // Straight: both wheels 10 rad/s, r 0.05: 0.5 m/s.
  for (int k = 0; k < 1000; ++k) o.update(10.0, 10.0, 0.05, 0.3, 0.001);
  EXPECT_NEAR(o.x(), 0.5, 1e-9);
  EXPECT_NEAR(o.y(), 0.0, 1e-12);
  EXPECT_NEAR(o.v(), 0.5, 1e-12);
  // A full circle on the spot: wheels -+ w b/2 / r.
  o.reset();
  const double w = 1.0, b = 0.3, r = 0.05;
  const int n = static_cast<int>(std::lround(2 * M_PI / w / 0.001));
  for (int k = 0; k < n; ++k) o.update(-w * b / 2 / r, w * b / 2 / r, r, b, 0.001);
  EXPECT_NEAR(o.theta(), 2 * M_PI, 1e-3);
  EXPECT_NEAR(o.x(), 0.0, 1e-12);
  EXPECT_NEAR(o.w(), 1.0, 1e-12);
  // An arc of radius R = v / w: after a quarter turn at (R, R).
  o.reset();
  const double v = 0.5, R = v / w;
  const int q = static_cast<int>(std::lround(M_PI / 2 / w / 0.001));
  for (int k = 0; k < q; ++k) o.update((v - w * b / 2) / r, (v + w * b / 2) / r, r, b, 0.001);
  EXPECT_NEAR(o.x(), R, 1e-3);
  EXPECT_NEAR(o.y(), R, 1e-3);
  // Backwards, the twist is negative (upstream: its magnitude).
  o.reset();
  o.update(-10.0, -10.0, 0.05, 0.3, 0.001);
  EXPECT_NEAR(o.v(), -0.5, 1e-12);
}

TEST(DriveMaths, WorldOdometryTurnsTheTwistIntoTheHeading) {
  LinkState s;
  s.X_WL = Eigen::Translation3d(1, 2, 0.3) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  s.v_W = Eigen::Vector3d(0.0, 0.5, 0.1);
  s.w_W = Eigen::Vector3d(0.1, 0.2, 0.4);
  DriveOdometry o;
  worldOdometry(s, true, &o);
  EXPECT_NEAR(o.linear.x(), 0.5, 1e-12);
  EXPECT_NEAR(o.linear.y(), 0.0, 1e-12);
  EXPECT_EQ(o.linear.z(), 0.0);
  EXPECT_EQ(o.angular, Eigen::Vector3d(0, 0, 0.4));
  EXPECT_EQ(o.position.z(), 0.3);
  worldOdometry(s, false, &o);
  EXPECT_EQ(o.position.z(), 0.0);
  EXPECT_EQ(o.X_OB.translation().z(), 0.3);  // the TF keeps the height
}

TEST(DriveCore, DiffDriveUpdatesOnItsGridAndCommandsTheWheels) {
  DriveConfig c = parseDriveConfig(plugin("libgazebo_ros_diff_drive.so",
                                          {{"wheelSeparation", "0.2"}, {"wheelDiameter", "0.1"},
                                           {"updateRate", "100"}}),
                                   "bot");
  DriveCore core(c);
  EXPECT_TRUE(core.setCommand(0.5, 0.3, 1.0, 0.0));
  EXPECT_FALSE(core.setCommand(std::nan(""), 0.0, 0.0, 0.0));
  EXPECT_FALSE(core.setCommand(0.0, 0.0, INFINITY, 0.0));
  LinkState model;
  std::vector<double> omega = {0.0, 0.0};
  int due = 0;
  std::vector<double> first;
  for (int k = 1; k <= 1000; ++k) {
    const DriveCore::Step& s = core.update(k * 0.001, model, omega);
    if (s.due) {
      ++due;
      EXPECT_TRUE(s.set_wheels);
      if (first.empty()) first = s.wheel_omega;
    } else {
      EXPECT_FALSE(s.set_wheels);
    }
  }
  EXPECT_NEAR(due, 100, 1);  // 100 Hz over 1 s
  // (0.5 -+ 1.0 * 0.1) / 0.05; the linear y of the command is not read.
  ASSERT_EQ(first.size(), 2u);
  EXPECT_NEAR(first[0], 8.0, 1e-12);
  EXPECT_NEAR(first[1], 12.0, 1e-12);
}

TEST(DriveCore, PlanarMoveOdometryFromPoseDifferences) {
  const DriveConfig c = parseDriveConfig(plugin("libgazebo_ros_planar_move.so",
                                                {{"odometryRate", "50"}}),
                                         "box");
  DriveCore core(c);
  core.setCommand(0.4, 0.1, 0.2, 0.0);
  LinkState model;
  int due = 0;
  double yaw = 0.0;
  Eigen::Vector2d p(0, 0);
  for (int k = 1; k <= 1000; ++k) {
    const double t = k * 0.001;
    const DriveCore::Step& s = core.update(t, model, {});
    ASSERT_TRUE(s.set_twist);
    // The velocity in the world is the command turned by the heading.
    EXPECT_NEAR(s.linear_W.x(), 0.4 * std::cos(yaw) - 0.1 * std::sin(yaw), 1e-9);
    EXPECT_NEAR(s.linear_W.y(), 0.1 * std::cos(yaw) + 0.4 * std::sin(yaw), 1e-9);
    EXPECT_EQ(s.angular_W.z(), 0.2);
    // Integrate as a perfect physics would.
    p += 0.001 * s.linear_W.head<2>();
    yaw += 0.001 * 0.2;
    model.X_WL = Eigen::Translation3d(p.x(), p.y(), 0.05) *
                 Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    if (s.due) ++due;
  }
  // t - last > 1/50, restarting from each publication: every 21 ms.
  EXPECT_EQ(due, 47);
  EXPECT_NEAR(core.odometry().linear.x(), 0.4, 1e-3);
  EXPECT_NEAR(core.odometry().linear.y(), 0.1, 1e-3);
  EXPECT_NEAR(core.odometry().angular.z(), 0.2, 1e-6);
  EXPECT_EQ(core.odometry().position.z(), 0.0);
}

TEST(DriveCore, PlanarMoveCommandTimeout) {
  const DriveConfig c = parseDriveConfig(plugin("libgazebo_ros_planar_move.so",
                                                {{"cmdTimeout", "0.1"}}),
                                         "box");
  DriveCore core(c);
  LinkState model;
  core.update(0.001, model, {});
  core.setCommand(1.0, 0.0, 0.0, 0.001);
  EXPECT_EQ(core.update(0.05, model, {}).linear_W.x(), 1.0);
  EXPECT_EQ(core.update(0.1, model, {}).linear_W.x(), 1.0);
  EXPECT_EQ(core.update(0.102, model, {}).linear_W.x(), 0.0);
}

TEST(DriveReport, TheStartUpTableListsTheDrivesAndTheirDifferences) {
  std::ifstream in(std::string(TEST_DATA_DIR) + "/urdf/diff_drive.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "<odometrySource>world</odometrySource>";
  RobotModel model = loadRobotModel(urdf, "diff_drive.urdf", LoadOptions());
  std::vector<ReportRow> rows = modelReport(model, "bot");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].type, "libgazebo_ros_diff_drive.so");
  EXPECT_EQ(rows[0].status, ReportRow::Status::kSimulated);
  EXPECT_EQ(rows[0].topics, (std::vector<std::string>{
                                "/bot/odom nav_msgs/Odometry @ 50 Hz",
                                "/bot/joint_states sensor_msgs/JointState @ 50 Hz",
                                "/bot/cmd_vel geometry_msgs/Twist (subscribed)"}));
  urdf.replace(urdf.find(from), from.size(), "<odometrySource>encoder</odometrySource>");
  model = loadRobotModel(urdf, "diff_drive.urdf", LoadOptions());
  rows = modelReport(model, "bot");
  EXPECT_EQ(rows[0].status, ReportRow::Status::kDifferences);
  EXPECT_TRUE(mentions(rows[0].notes, "encoder odometry's linear.x is signed"));
}

TEST(DriveReport, ForceAndTemplateAreLeftOutWithTheirReasons) {
  EXPECT_NE(leftOutPluginReason("libgazebo_ros_force.so").find("/gazebo/apply_body_wrench"),
            std::string::npos);
  EXPECT_NE(leftOutPluginReason("/usr/lib/libgazebo_ros_template.so").find("empty example"),
            std::string::npos);
  EXPECT_EQ(leftOutPluginReason("libfoo.so"), "");
}

}  // namespace
}  // namespace tianracer_sim
