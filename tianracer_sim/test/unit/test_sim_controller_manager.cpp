// A robot spawned without controllers, then driven by controllers loaded, started, stopped and
// unloaded by name (what the controller_manager services do), in sim time.
#include <cmath>

#include <gtest/gtest.h>

#include "sim_test_support.h"

namespace tianracer_sim {
namespace {

namespace tc = tianracer_control;

const char* kLeftWheel = "left_rear_wheel_velocity_controller";
const char* kRightWheel = "right_rear_wheel_velocity_controller";

class ControllerManagerSim : public ::testing::Test {
 protected:
  void SetUp() override {
    // No controller, as after spawn_model.
    robot_ = &sim_.addRobot(test::tianracerAt(Eigen::Vector3d(0, 0, test::kSpawnZ + 0.001)));
  }
  PhysicsRobot& physics() { return sim_.physics().robot(robot_->id); }
  void run(double seconds) {
    const auto n = static_cast<long>(std::lround(seconds / sim_.dt()));
    for (long i = 0; i < n; ++i) sim_.step();
  }
  void loadShipped() {
    for (const tc::ControllerSpec& spec : test::shippedControllers()) sim_.controllerManager().load(*robot_, spec);
  }
  double wheelVelocity(const std::string& joint) {
    return physics().jointVelocity(physics().jointIndex(joint));
  }
  double distance() { return physics().basePose().translation().head<2>().norm(); }
  std::vector<std::string> allNames() {
    std::vector<std::string> names;
    for (const auto& c : robot_->controllers.controllers()) names.push_back(c->name());
    return names;
  }

  Simulation sim_;
  SimRobot* robot_ = nullptr;
};

TEST_F(ControllerManagerSim, LoadedControllersDoNothingUntilStarted) {
  loadShipped();
  ASSERT_EQ(robot_->controllers.size(), 5u);
  robot_->controllers.find(kLeftWheel)->setCommand(20.0);
  robot_->controllers.find(kRightWheel)->setCommand(20.0);
  run(1.0);
  EXPECT_LT(distance(), 0.005);  // loaded, not running: the wheels stay free

  sim_.controllerManager().switchControllers(*robot_, allNames(), {}, tc::Strictness::kStrict);
  // starting(): velocity controllers start at 0, so the car holds still...
  run(0.5);
  EXPECT_LT(distance(), 0.005);
  // ...until commanded: 20 rad/s * 0.032 m for 1 s, straight ahead (the hinges, free until
  // now, hold where they were when they started).
  robot_->controllers.find("left_steering_hinge_position_controller")->setCommand(0.0);
  robot_->controllers.find("right_steering_hinge_position_controller")->setCommand(0.0);
  robot_->controllers.find(kLeftWheel)->setCommand(20.0);
  robot_->controllers.find(kRightWheel)->setCommand(20.0);
  run(1.0);
  EXPECT_GT(distance(), 0.4);
}

TEST_F(ControllerManagerSim, AStoppedWheelControllerLetsItsJointGo) {
  loadShipped();
  sim_.controllerManager().switchControllers(*robot_, allNames(), {}, tc::Strictness::kStrict);
  tc::Controller& left = *robot_->controllers.find(kLeftWheel);
  tc::Controller& right = *robot_->controllers.find(kRightWheel);
  // The right wheel holds 0; the left one spins the car round it.
  left.setCommand(15.0);
  run(1.0);
  EXPECT_NEAR(wheelVelocity("left_rear_wheel_joint"), 15.0, 0.5);

  sim_.controllerManager().switchControllers(*robot_, {}, {kLeftWheel}, tc::Strictness::kStrict);
  EXPECT_FALSE(robot_->controllers.isRunning(left));
  left.setCommand(30.0);  // no longer followed
  run(1.0);
  EXPECT_LT(std::fabs(wheelVelocity("left_rear_wheel_joint")), 1.0);
  EXPECT_NEAR(wheelVelocity("right_rear_wheel_joint"), 0.0, 0.2);
  (void)right;

  // Started again, it follows from 0 (starting()), then the new command.
  sim_.controllerManager().switchControllers(*robot_, {kLeftWheel}, {}, tc::Strictness::kStrict);
  EXPECT_EQ(left.command(), 0.0);
  left.setCommand(10.0);
  run(1.0);
  EXPECT_NEAR(wheelVelocity("left_rear_wheel_joint"), 10.0, 0.5);
}

TEST_F(ControllerManagerSim, UnloadAndErrorsLeaveTheRobotRunning) {
  loadShipped();
  sim_.controllerManager().switchControllers(*robot_, allNames(), {}, tc::Strictness::kStrict);
  EXPECT_THROW(sim_.controllerManager().unload(*robot_, kLeftWheel), tc::ControllerError);
  EXPECT_THROW(sim_.controllerManager().switchControllers(*robot_, {"nope"}, {}, tc::Strictness::kStrict),
               tc::ControllerError);
  tc::ControllerSpec unknown;
  unknown.name = "dd";
  unknown.type = "no_such_controllers/NoSuchController";
  EXPECT_THROW(sim_.controllerManager().load(*robot_, unknown), tc::ControllerError);
  sim_.controllerManager().switchControllers(*robot_, {}, allNames(), tc::Strictness::kStrict);
  for (const std::string& name : allNames()) sim_.controllerManager().unload(*robot_, name);
  EXPECT_TRUE(robot_->controllers.empty());
  run(1.0);
  EXPECT_TRUE(physics().basePose().matrix().allFinite());
  // Loadable again after an unload.
  loadShipped();
  EXPECT_EQ(robot_->controllers.size(), 5u);
}

}  // namespace
}  // namespace tianracer_sim
