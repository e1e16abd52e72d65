// The environment core without ROS: the node's files in, only the observed outputs computed,
// the cmd_vel node's Ackermann maths onto the controllers, resets and reseeds that repeat.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>

#include <tianracer_control/ackermann.h>

#include "sim_test_support.h"
#include "tianracer_sim/env/sim_env.h"

namespace tianracer_sim {
namespace {

EnvConfig tianracer(std::vector<std::string> observe) {
  test::loadTianracer();  // ROS_PACKAGE_PATH for xacro's $(find)
  EnvConfig c;
  c.model = test::descriptionDir() + "/urdf/tianracer_description.xacro";
  c.control_config = test::repoDir() + "/tianracer_control/config/tianracer_control.yaml";
  c.world = "racetrack";
  c.observe = std::move(observe);
  c.find_package = [](const std::string& pkg) -> std::string {
    if (pkg == "tianracer_description") return test::descriptionDir();
    if (pkg == "tianracer_sim") return test::repoDir() + "/tianracer_sim";
    return "";
  };
  return c;
}

std::vector<float> scanOf(const SimEnv& env) {
  std::vector<float> r(env.observations()[0].bytes() / sizeof(float));
  env.read(0, r.data());
  return r;
}

TEST(SimEnv, ComputesOnlyWhatIsObserved) {
  SimEnv env(tianracer({"odom"}));
  env.step(100);
  for (const auto& s : env.simulator().sensors()) EXPECT_EQ(s->stat().renders, 0u) << s->name();
  SimEnv scanning(tianracer({"scan"}));
  scanning.step(100);
  for (const auto& s : scanning.simulator().sensors()) {
    EXPECT_EQ(s->stat().renders > 0, s->name() == "hokuyo_sensor") << s->name();
  }
  EXPECT_EQ(scanning.observations()[0].shape, std::vector<std::size_t>{1081});
  scanning.step(10);
  EXPECT_NEAR(scanning.observations()[0].stamp, 0.1, 1e-9);  // 40 Hz: held until 0.125
}

TEST(SimEnv, AckermannGoesThroughTheCmdVelNodesMaths) {
  EnvConfig config = tianracer({"odom"});
  config.world = "empty";  // room to turn
  SimEnv env(config);
  ASSERT_NE(env.ackermann(), nullptr) << env.ackermannProblem();
  const tianracer_control::AckermannGeometry& g = env.ackermann()->geometry();
  EXPECT_NEAR(g.wheelbase, 0.25, 1e-3);  // the seed's joint layout
  EXPECT_NEAR(g.wheel_radius, 0.032, 1e-6);
  env.setAckermann(1.0, 0.2);
  const tianracer_control::AckermannCommand want = tianracer_control::ackermannFromSteering(g, 1.0, 0.2);
  const auto& names = env.ackermann()->controllers();
  auto command = [&](int k) {
    return env.simulator().robot(env.robot())->controllers.find(names[k])->command();
  };
  EXPECT_EQ(command(0), want.left_steer);
  EXPECT_EQ(command(1), want.right_steer);
  EXPECT_EQ(command(2), want.left_wheel_omega);
  EXPECT_EQ(command(3), want.right_wheel_omega);
  EXPECT_GT(want.left_steer, want.right_steer);  // turning left: the left wheel is the inner one
  EXPECT_THROW(env.setAckermann(NAN, 0.0), EnvError);
  env.step(1000);
  double odom[13];
  env.odom(odom);
  EXPECT_GT(odom[7], 0.8);  // body forward speed near 1 m/s
  EXPECT_GT(odom[12], 0.5);  // turning left
}

TEST(SimEnv, ResetAndReseedRepeat) {
  SimEnv env(tianracer({"scan", "odom"}));
  auto run = [&](std::uint64_t seed) {
    env.reseed(seed);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Eigen::Vector3d(1.0, 0.05, 0.0);
    env.reset(X);
    env.setAckermann(1.5, 0.1);
    env.step(300);
    return scanOf(env);
  };
  const std::vector<float> a = run(5), b = run(5), c = run(6);
  ASSERT_EQ(a.size(), 1081u);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
  EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0);  // other noise
  double odom[13];
  env.odom(odom);
  EXPECT_NEAR(env.time(), 0.3, 1e-9);
  EXPECT_GT(odom[0], 1.2);
}

TEST(SimEnv, ResetPutsTheRobotOnTheGroundWhereAsked) {
  SimEnv env(tianracer({"odom"}));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(-2.0, 0.1, 5.0);  // z is replaced: resting on the ground
  X.linear() = Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  env.reset(X);
  double odom[13];
  env.odom(odom);
  EXPECT_DOUBLE_EQ(odom[0], -2.0);
  EXPECT_NEAR(odom[2], test::kSpawnZ, 2e-3);
  EXPECT_EQ(env.time(), 0.0);
  X.translation().x() = NAN;
  EXPECT_THROW(env.reset(X), EnvError);
}

TEST(SimEnv, AfterAResetSensorsSeeTheRobotWhereItNowIs) {
  // The scene is refreshed once per step count; a reset brings the count back to a value it
  // had, so the reset must refresh it (else the t = 0 scan sees the robot where it was).
  SimEnv env(tianracer({"scan"}));
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(2.0, 0.2, 0.0);
  env.reset(X);
  const Scene& scene = env.simulator().scene();
  bool found = false;
  for (const SceneBody& b : scene.bodies) {
    if (b.name != "tianracer::chassis") continue;
    found = true;
    const Eigen::Isometry3d X_WL =
        env.simulator().linkPose(LinkRef{env.robot(), "chassis"});
    EXPECT_LT((b.X_WB.translation() - X_WL.translation()).norm(), 1e-9);
  }
  EXPECT_TRUE(found);
}

TEST(SimEnv, BadObservationsNameWhatExists) {
  try {
    SimEnv env(tianracer({"odom", "front_lidar"}));
    FAIL();
  } catch (const EnvError& e) {
    EXPECT_NE(std::string(e.what()).find("observation 'front_lidar': the model has no such "
                                         "sensor; its sensors: camera1 (camera), hokuyo_sensor "
                                         "(lidar), real_sense (depth_camera)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(SimEnv(tianracer({"odom", "odom"})), EnvError);
  EXPECT_THROW(SimEnv(tianracer({"hokuyo_sensor/image"})), EnvError);
  EnvConfig no_yaml = tianracer({"odom"});
  no_yaml.control_config.clear();
  SimEnv bare(no_yaml);
  EXPECT_EQ(bare.ackermann(), nullptr);
  EXPECT_NE(bare.ackermannProblem().find("no controller with a command drives joint(s)"),
            std::string::npos);
  EXPECT_THROW(bare.setAckermann(1.0, 0.0), EnvError);
}

}  // namespace
}  // namespace tianracer_sim
