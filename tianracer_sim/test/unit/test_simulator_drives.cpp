// The drive plugins (diff drive, skid steer, planar_move) in the Simulator: a command moves the
// robot or world model at the commanded speed and yaw rate (ground truth, within 3 %), the
// odometry follows it, and a plugin with bad input is left out with the reason while the model
// runs on.
#include <gtest/gtest.h>

#include <regex>

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/drives/sim_drive.h"
#include "tianracer_sim/simulator/simulator.h"

#include "common_test_support.h"
#include "sim_test_support.h"

namespace tianracer_sim {
namespace {

const std::string kData = TEST_DATA_DIR;

using test::groundWorld;

RobotSpawn robot(const std::string& file, const std::string& name) {
  RobotSpawn spawn;
  spawn.name = name;
  spawn.model = loadRobotModelFile(kData + "/urdf/" + file, LoadOptions());
  spawn.drop_to_ground = true;
  return spawn;
}

RobotSpawn robotFromText(const std::string& urdf, const std::string& name) {
  RobotSpawn spawn;
  spawn.name = name;
  spawn.model = loadRobotModel(urdf, name, LoadOptions());
  spawn.drop_to_ground = true;
  return spawn;
}

double yawOfModel(const Simulator& sim, ModelId id) {
  return yawOf(Eigen::Quaterniond(sim.modelState(id).X_WE.rotation()));
}

/// Mean forward speed and yaw rate of the model over `seconds` after `settle` s.
struct Motion {
  double v = 0.0, w = 0.0;
};
Motion measure(Simulator& sim, ModelId id, double settle, double seconds) {
  sim.step(static_cast<int>(std::lround(settle / sim.dt())));
  const Eigen::Isometry3d X0 = sim.modelState(id).X_WE;
  double yaw = yawOfModel(sim, id), turned = 0.0, path = 0.0;
  Eigen::Vector3d p = X0.translation();
  const int n = static_cast<int>(std::lround(seconds / sim.dt()));
  for (int k = 0; k < n; ++k) {
    sim.step();
    const Eigen::Isometry3d X = sim.modelState(id).X_WE;
    double y = yawOf(Eigen::Quaterniond(X.rotation()));
    double d = y - yaw;
    while (d > M_PI) d -= 2 * M_PI;
    while (d < -M_PI) d += 2 * M_PI;
    turned += d;
    yaw = y;
    const Eigen::Vector3d step = X.translation() - p;
    const Eigen::Vector3d heading = X.rotation() * Eigen::Vector3d::UnitX();
    path += step.dot(heading);
    p = X.translation();
  }
  return {path / seconds, turned / seconds};
}

SimDrive* driveOf(Simulator& sim, ModelId id, const std::string& name) {
  return dynamic_cast<SimDrive*>(sim.findSensor(id, name));
}

/// A world of `models` on the ground, its model `model` and that model's drive plugin `plugin`
/// (kNoModel and null where missing).
struct WorldModelDrive {
  Simulator sim;
  ModelId id;
  SimDrive* drive;
  WorldModelDrive(const std::string& models, const std::string& model, const std::string& plugin)
      : sim(groundWorld(models), {}),
        id(sim.findModel(model)),
        drive(id == kNoModel ? nullptr : driveOf(sim, id, plugin)) {}
  /// Whether both are there; if not, why not (the plugins left out of the model and why).
  ::testing::AssertionResult found() const {
    if (id == kNoModel) return ::testing::AssertionFailure() << "no such model";
    if (drive == nullptr) {
      return ::testing::AssertionFailure() << ::testing::PrintToString(sim.leftOut(id));
    }
    return ::testing::AssertionSuccess();
  }
};

/// After `rest` steps at rest, commands v = 0.5 m/s and w = 0.5 rad/s: over 2 s, from `settle`
/// s on, the model moves at them and the odometry reports the speed.
void expectDrivesTheArc(WorldModelDrive& w, int rest, double settle) {
  w.sim.step(rest);
  w.drive->setCommand(0.5, 0.0, 0.5);
  const Motion m = measure(w.sim, w.id, settle, 2.0);
  EXPECT_NEAR(m.v, 0.5, 0.015);
  EXPECT_NEAR(m.w, 0.5, 0.015);
  EXPECT_NEAR(w.drive->odometry().linear.x(), 0.5, 0.015);
}

TEST(Drives, DiffDriveMovesAtTheCommandedSpeedAndYawRate) {
  Simulator sim(groundWorld(), {});
  const ModelId id = sim.addRobot(robot("diff_drive.urdf", "diff_bot"));
  SimDrive* drive = driveOf(sim, id, "diff_drive");
  ASSERT_NE(drive, nullptr) << ::testing::PrintToString(sim.leftOut(id));
  EXPECT_EQ(drive->config().commandTopic(), "/diff_bot/cmd_vel");  // the model's name
  EXPECT_EQ(drive->config().odometryTopic(), "/diff_bot/odom");
  sim.step(200);
  ASSERT_TRUE(drive->setCommand(0.5, 0.0, 0.0));
  Motion m = measure(sim, id, 1.0, 2.0);
  EXPECT_NEAR(m.v, 0.5, 0.015);
  EXPECT_NEAR(m.w, 0.0, 0.015);
  // The odometry (world source) is the model's motion, in the base frame.
  EXPECT_NEAR(drive->odometry().linear.x(), 0.5, 0.015);
  EXPECT_NEAR(drive->odometry().position.x(), sim.modelState(id).X_WE.translation().x(), 0.011);

  ASSERT_TRUE(drive->setCommand(0.0, 0.0, 0.5));
  m = measure(sim, id, 1.0, 2.0);
  EXPECT_NEAR(m.w, 0.5, 0.015);
  EXPECT_NEAR(m.v, 0.0, 0.015);
  EXPECT_NEAR(drive->odometry().angular.z(), 0.5, 0.015);

  ASSERT_TRUE(drive->setCommand(0.5, 0.0, 0.5));
  m = measure(sim, id, 1.0, 2.0);
  EXPECT_NEAR(m.v, 0.5, 0.015);
  EXPECT_NEAR(m.w, 0.5, 0.015);

  // A non-finite command is refused, the last one stays.
  EXPECT_FALSE(drive->setCommand(std::nan(""), 0.0, 0.0));
  m = measure(sim, id, 0.0, 1.0);
  EXPECT_NEAR(m.v, 0.5, 0.015);
  EXPECT_TRUE(sim.modelState(id).X_WE.matrix().allFinite());
}

TEST(Drives, DiffDriveEncoderOdometryFollowsTheWheels) {
  std::string urdf;
  {
    std::ifstream in(kData + "/urdf/diff_drive.urdf");
    urdf.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string from = "<odometrySource>world</odometrySource>";
  urdf.replace(urdf.find(from), from.size(), "<odometrySource>encoder</odometrySource>");
  Simulator sim(groundWorld(), {});
  const ModelId id = sim.addRobot(robotFromText(urdf, "enc_bot"));
  SimDrive* drive = driveOf(sim, id, "diff_drive");
  ASSERT_NE(drive, nullptr);
  const Eigen::Vector3d start = sim.modelState(id).X_WE.translation();
  drive->setCommand(-0.4, 0.0, 0.3);
  sim.step(3000);
  const Eigen::Isometry3d X = sim.modelState(id).X_WE;
  const DriveOdometry& o = drive->odometry();
  // Odometry starts at 0 in its own frame; the robot started facing +x.
  EXPECT_NEAR(o.position.x(), X.translation().x() - start.x(), 0.02);
  EXPECT_NEAR(o.position.y(), X.translation().y() - start.y(), 0.02);
  EXPECT_NEAR(yawOf(o.orientation), yawOfModel(sim, id), 0.03);
  EXPECT_NEAR(o.linear.x(), -0.4, 0.02);  // signed (upstream: its magnitude)
  EXPECT_NEAR(o.angular.z(), 0.3, 0.02);
  EXPECT_EQ(o.position.z(), 0.0);
  // reset_simulation: the odometry starts again from 0, the wheels are held.
  sim.resetSimulation();
  drive->setCommand(0.0, 0.0, 0.0);
  sim.step(100);
  EXPECT_NEAR(drive->odometry().position.norm(), 0.0, 1e-3);
  EXPECT_NEAR((sim.modelState(id).X_WE.translation() - start).norm(), 0.0, 2e-3);
}

TEST(Drives, SkidSteerMovesAtTheCommandedSpeedAndTurnsAsFrictionAllows) {
  Simulator sim(groundWorld(), {});
  const ModelId id = sim.addRobot(robot("skid_steer.urdf", "skid_bot"));
  SimDrive* drive = driveOf(sim, id, "skid_steer");
  ASSERT_NE(drive, nullptr) << ::testing::PrintToString(sim.leftOut(id));
  EXPECT_EQ(drive->config().commandTopic(), "/skid/cmd_vel");
  sim.step(200);
  drive->setCommand(0.5, 0.0, 0.0);
  Motion m = measure(sim, id, 1.0, 2.0);
  EXPECT_NEAR(m.v, 0.5, 0.015);
  EXPECT_NEAR(m.w, 0.0, 0.015);
  EXPECT_NEAR(drive->odometry().linear.x(), 0.5, 0.015);
  EXPECT_EQ(drive->odometry().position.z(), 0.0);  // the skid steer leaves z out
  EXPECT_EQ(drive->odometry().pose_covariance[7], 0.002);
  EXPECT_EQ(drive->odometry().twist_covariance[35], 0.03);
  // Turning on the spot, the wheels scrub sideways: the yaw rate is what friction leaves of
  // the commanded one (the plugin's kinematics assume no slip), and the odometry (world
  // source) reports the real one.
  drive->setCommand(0.0, 0.0, 0.5);
  m = measure(sim, id, 1.0, 2.0);
  EXPECT_GT(m.w, 0.25);
  EXPECT_LT(m.w, 0.5);
  EXPECT_NEAR(yawOf(drive->odometry().orientation), yawOfModel(sim, id), 0.01);
}

const char kPlanarBox[] =
    "<model name='mover'><pose>0 0 0.1 0 0 0</pose><link name='body'><inertial><mass>5</mass>"
    "<inertia><ixx>0.03</ixx><iyy>0.03</iyy><izz>0.03</izz></inertia></inertial>"
    "<collision name='c'><geometry><box><size>0.3 0.3 0.2</size></box></geometry>"
    "<surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction></surface></collision></link>"
    "<plugin name='planar' filename='libgazebo_ros_planar_move.so'>"
    "<commandTopic>cmd_vel</commandTopic><odometryTopic>odom</odometryTopic>"
    "<odometryFrame>odom</odometryFrame><odometryRate>50</odometryRate>"
    "<robotBaseFrame>mover</robotBaseFrame></plugin></model>";

TEST(Drives, PlanarMoveSetsAWorldModelsVelocity) {
  WorldModelDrive w(kPlanarBox, "mover", "planar");
  ASSERT_TRUE(w.found());
  EXPECT_EQ(w.drive->config().commandTopic(), "/cmd_vel");
  expectDrivesTheArc(w, 200, 0.5);
  EXPECT_NEAR(w.drive->odometry().angular.z(), 0.5, 0.015);
  // Sideways in the model's frame.
  w.drive->setCommand(0.0, 0.3, 0.0);
  w.sim.step(500);
  EXPECT_NEAR(w.drive->odometry().linear.y(), 0.3, 0.01);
  EXPECT_NEAR(w.drive->odometry().linear.x(), 0.0, 0.01);
}

// A world model with wheels on revolute joints and a frictionless caster ball: the diff drive
// drives a world model's joints as a robot's.
const char kWheeledModel[] =
    "<model name='cart'><pose>0 0 0.06 0 0 0</pose>"
    "<link name='chassis'><inertial><mass>2</mass><inertia><ixx>0.01</ixx><iyy>0.02</iyy>"
    "<izz>0.025</izz></inertia></inertial>"
    "<collision name='box'><pose>0 0 0.03 0 0 0</pose><geometry><box><size>0.3 0.2 0.04</size>"
    "</box></geometry></collision>"
    "<collision name='caster'><pose>0.12 0 -0.038 0 0 0</pose><geometry><sphere><radius>0.02"
    "</radius></sphere></geometry><surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction>"
    "</surface></collision>"
    "<collision name='caster2'><pose>-0.12 0 -0.038 0 0 0</pose><geometry><sphere><radius>0.02"
    "</radius></sphere></geometry><surface><friction><ode><mu>0</mu><mu2>0</mu2></ode></friction>"
    "</surface></collision></link>"
    "<link name='left'><pose>0 0.12 0 0 0 0</pose><inertial><mass>0.2</mass><inertia>"
    "<ixx>0.00013</ixx><iyy>0.00025</iyy><izz>0.00013</izz></inertia></inertial>"
    "<collision name='c'><pose>0 0 0 1.5707963 0 0</pose><geometry><cylinder><radius>0.06</radius>"
    "<length>0.02</length></cylinder></geometry><surface><friction><ode><mu>1</mu><mu2>1</mu2>"
    "</ode></friction></surface></collision></link>"
    "<link name='right'><pose>0 -0.12 0 0 0 0</pose><inertial><mass>0.2</mass><inertia>"
    "<ixx>0.00013</ixx><iyy>0.00025</iyy><izz>0.00013</izz></inertia></inertial>"
    "<collision name='c'><pose>0 0 0 1.5707963 0 0</pose><geometry><cylinder><radius>0.06</radius>"
    "<length>0.02</length></cylinder></geometry><surface><friction><ode><mu>1</mu><mu2>1</mu2>"
    "</ode></friction></surface></collision></link>"
    "<joint name='left_joint' type='revolute'><parent>chassis</parent><child>left</child>"
    "<axis><xyz>0 1 0</xyz><limit><lower>-1e16</lower><upper>1e16</upper></limit></axis></joint>"
    "<joint name='right_joint' type='revolute'><parent>chassis</parent><child>right</child>"
    "<axis><xyz>0 1 0</xyz><limit><lower>-1e16</lower><upper>1e16</upper></limit></axis></joint>"
    "<plugin name='drive' filename='libgazebo_ros_diff_drive.so'><robotNamespace>cart</robotNamespace>"
    "<wheelSeparation>0.24</wheelSeparation><wheelDiameter>0.12</wheelDiameter>"
    "<updateRate>100</updateRate><publishTf>true</publishTf></plugin></model>";

TEST(Drives, DiffDriveDrivesAWorldModelsJoints) {
  WorldModelDrive w(kWheeledModel, "cart", "drive");
  ASSERT_TRUE(w.found());
  EXPECT_EQ(w.drive->config().commandTopic(), "/cart/cmd_vel");
  expectDrivesTheArc(w, 300, 1.0);
}

TEST(Drives, PlanarMoveCommandsExpireAfterCmdTimeout) {
  std::string box = kPlanarBox;
  box.replace(box.find("</plugin>"), 9, "<cmdTimeout>0.2</cmdTimeout></plugin>");
  WorldModelDrive w(box, "mover", "planar");
  ASSERT_TRUE(w.found());
  w.sim.step(100);
  w.drive->setCommand(0.5, 0.0, 0.0);
  w.sim.step(150);
  EXPECT_NEAR(w.sim.modelState(w.id).V_WE.linear.x(), 0.5, 0.01);
  w.sim.step(200);  // 0.35 s after the command
  EXPECT_NEAR(w.sim.modelState(w.id).V_WE.linear.x(), 0.0, 0.01);
}

std::string withPlugin(const std::string& file, const std::string& from, const std::string& to) {
  return test::replaced(test::readFile(kData + "/urdf/" + file), from, to);
}

TEST(Drives, BadPluginsAreLeftOutWithTheReasonAndTheRobotRunsOn) {
  struct Case {
    std::string file, from, to, expect;
  };
  const std::vector<Case> cases = {
      {"diff_drive.urdf", "<leftJoint>left_wheel_joint</leftJoint>", "<leftJoint>nope</leftJoint>",
       "libgazebo_ros_diff_drive.so plugin 'diff_drive' of model 'bad': <leftJoint> 'nope' is not a "
       "movable joint of the model"},
      {"diff_drive.urdf", "<wheelDiameter>0.1</wheelDiameter>", "<wheelDiameter>0</wheelDiameter>",
       "diff_drive plugin 'diff_drive' of model 'bad': <wheelDiameter> 0 must be > 0"},
      {"diff_drive.urdf", "<wheelDiameter>0.1</wheelDiameter>", "<wheelDiameter>-0.1</wheelDiameter>",
       "<wheelDiameter> -0.1 must be > 0"},
      {"diff_drive.urdf", "<odometrySource>world</odometrySource>",
       "<odometrySource>gps</odometrySource>", "<odometrySource> 'gps' is neither encoder nor world"},
      {"skid_steer.urdf", "<rightRearJoint>right_rear_wheel_joint</rightRearJoint>",
       "<rightRearJoint>base_link</rightRearJoint>",
       "skid_steer_drive.so plugin 'skid_steer' of model 'bad': <rightRearJoint> 'base_link' is not "
       "a movable joint"},
      {"skid_steer.urdf", "<torque>5</torque>", "<torque>lots</torque>", "<torque> 'lots' is not a number"},
  };
  for (const Case& c : cases) {
    Simulator sim(groundWorld(), {});
    std::vector<std::string> errors;
    const ModelId id = sim.addRobot(robotFromText(withPlugin(c.file, c.from, c.to), "bad"));
    const LeftOut& out = sim.leftOut(id);
    const std::string name = c.file == "diff_drive.urdf" ? "diff_drive" : "skid_steer";
    ASSERT_EQ(out.count(name), 1u) << c.to;
    EXPECT_NE(out.at(name).find(c.expect), std::string::npos) << out.at(name);
    // Placed at the <plugin>, whether its parameters or the model refuse it.
    EXPECT_TRUE(std::regex_search(out.at(name), std::regex(":[0-9]+: "))) << out.at(name);
    EXPECT_EQ(driveOf(sim, id, name), nullptr);
    // The robot and its other plugin run on.
    EXPECT_NE(sim.findSensor(id, "truth"), nullptr);
    sim.step(100);
    EXPECT_TRUE(sim.modelState(id).X_WE.matrix().allFinite());
  }
}

TEST(Drives, AForcePluginOnAWorldModelIsNamedWithItsReason) {
  std::string box = kPlanarBox;
  box.replace(box.find("</model>"), 8,
              "<plugin name='push' filename='libgazebo_ros_force.so'><bodyName>body</bodyName>"
              "<topicName>force</topicName></plugin></model>");
  std::vector<std::string> warnings;
  SimulatorOptions options;
  options.log.warn = [&](const std::string& w) { warnings.push_back(w); };
  Simulator sim(groundWorld(box), options);
  int named = 0;
  for (const std::string& w : warnings) {
    named += w.find("model 'mover': plugin 'push' (libgazebo_ros_force.so) is not simulated; "
                    "ignored: libgazebo_ros_force") != std::string::npos &&
             w.find("/gazebo/apply_body_wrench") != std::string::npos;
  }
  EXPECT_EQ(named, 1) << ::testing::PrintToString(warnings);
  EXPECT_NE(driveOf(sim, sim.findModel("mover"), "planar"), nullptr);  // the rest runs
}

TEST(Drives, PlanarMoveOnAStaticModelIsLeftOut) {
  std::string box = kPlanarBox;
  box.replace(box.find("<pose>"), 6, "<static>true</static><pose>");
  Simulator sim(groundWorld(box), {});
  const ModelId id = sim.findModel("mover");
  ASSERT_EQ(sim.leftOut(id).count("planar"), 1u);
  EXPECT_NE(sim.leftOut(id).at("planar").find("the model is static"), std::string::npos);
  sim.step(10);
}

}  // namespace
}  // namespace tianracer_sim
