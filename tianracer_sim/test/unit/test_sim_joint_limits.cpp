// A position command beyond a joint's URDF limit, through the simulation's hardware
// (Simulation::read/write): arm_control.urdf's finger (prismatic, 0 to 0.08 m, 0.5 m/s) under
// position_controllers/JointPositionController is commanded past each limit; the command that
// reaches the joint is the limit and the finger stops there (DefaultRobotHWSim's
// PositionJointSaturationHandle bound; issue 39, point 3). The controller clamps the command
// too (clampToPositionLimits), and the hardware (sim/robot_hw_sim.h) as DefaultRobotHWSim
// does; this test holds either way (test_sim_hw_sim checks the hardware alone).
#include <cmath>

#include <gtest/gtest.h>

#include "sim_test_support.h"
#include "tianracer_control/controller_yaml.h"

namespace tianracer_sim {
namespace {

class JointLimitsSim : public ::testing::Test {
 protected:
  void SetUp() override {
    RobotConfig config;
    config.name = "arm";
    config.model = loadRobotModelFile(
        test::repoDir() + "/tianracer_sim/test/data/urdf/arm_control.urdf", LoadOptions());
    config.drop_to_ground = true;
    config.controllers = tianracer_control::loadControllerYaml(
        "arm:\n"
        "  finger_controller:\n"
        "    type: position_controllers/JointPositionController\n"
        "    joint: finger_joint\n"
        "  arm_controller:\n"
        "    type: position_controllers/JointGroupPositionController\n"
        "    joints: [shoulder_joint, elbow_joint]\n",
        "test_sim_joint_limits", "arm");
    robot_ = &sim_.addRobot(std::move(config));
    PhysicsRobot& pr = sim_.physics().robot(robot_->id);
    finger_joint_ = pr.jointIndex("finger_joint");
    for (size_t k = 0; k < robot_->handles.size(); ++k) {
      if (robot_->handles[k].name == "finger_joint") handle_ = k;
    }
  }
  void run(double seconds) {
    const auto n = static_cast<long>(std::lround(seconds / sim_.dt()));
    for (long i = 0; i < n; ++i) sim_.step();
  }
  double finger() { return sim_.physics().robot(robot_->id).jointPosition(finger_joint_); }

  Simulation sim_;
  SimRobot* robot_ = nullptr;
  int finger_joint_ = -1;
  size_t handle_ = 0;
};

TEST_F(JointLimitsSim, APositionCommandPastALimitStopsAtTheLimit) {
  tianracer_control::Controller* c = robot_->controllers.find("finger_controller");
  ASSERT_NE(c, nullptr);
  ASSERT_EQ(robot_->handles[handle_].name, "finger_joint");
  c->setCommand(0.2);  // upper limit 0.08
  run(0.5);            // 0.08 m at 0.5 m/s: 0.16 s
  EXPECT_DOUBLE_EQ(robot_->handles[handle_].command, 0.08);
  EXPECT_NEAR(finger(), 0.08, 1e-3);
  run(0.5);
  EXPECT_NEAR(finger(), 0.08, 1e-3);
  std::cout << "finger at " << finger() << " m for a command of 0.2 m\n";

  c->setCommand(-1.0);  // lower limit 0
  run(0.5);
  EXPECT_DOUBLE_EQ(robot_->handles[handle_].command, 0.0);
  EXPECT_NEAR(finger(), 0.0, 1e-3);
  std::cout << "finger at " << finger() << " m for a command of -1 m\n";
}

}  // namespace
}  // namespace tianracer_sim
