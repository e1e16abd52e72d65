// Physics regression of the tianracer driven through its shipped controllers.
// Sim time only: each test calls step() and never sleeps. Figures are printed for the notes.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "sim_test_support.h"

namespace tianracer_sim {
namespace {

namespace tc = tianracer_control;

class TianracerSim : public ::testing::Test {
 protected:
  void SetUp() override {
    RobotConfig config = test::tianracerAt(Eigen::Vector3d(0, 0, test::kSpawnZ + 0.001));
    config.controllers = test::shippedControllers();
    robot_ = &sim_.addRobot(std::move(config));
  }

  PhysicsRobot& physics() { return sim_.physics().robot(robot_->id); }
  tc::Controller& controller(const std::string& name) {
    tc::Controller* c = robot_->controllers.find(name);
    EXPECT_NE(c, nullptr) << name;
    return *c;
  }
  void setSpeed(double v) {
    controller("left_rear_wheel_velocity_controller").setCommand(v / test::kWheelRadius);
    controller("right_rear_wheel_velocity_controller").setCommand(v / test::kWheelRadius);
  }
  void setSteer(double left, double right) {
    controller("left_steering_hinge_position_controller").setCommand(left);
    controller("right_steering_hinge_position_controller").setCommand(right);
  }
  void run(double seconds) {
    const auto n = static_cast<long>(std::lround(seconds / sim_.dt()));
    for (long i = 0; i < n; ++i) sim_.step();
  }
  double yaw() {
    const Eigen::Matrix3d R = physics().basePose().linear();
    return std::atan2(R(1, 0), R(0, 0));
  }

  Simulation sim_;
  SimRobot* robot_ = nullptr;
};

TEST_F(TianracerSim, AtRestWithZeroCommandMovesLessThan1mmIn60s) {
  run(1.0);  // settle on the ground
  const Eigen::Vector3d p0 = physics().basePose().translation();
  run(60.0);
  const double moved = (physics().basePose().translation() - p0).norm();
  std::printf("[figure] (a) at rest, zero command, 60 s: base moved %.4f mm\n", moved * 1e3);
  EXPECT_LT(moved, 1e-3);
}

TEST_F(TianracerSim, OneMeterPerSecondIsReachedWithin1PercentAndDriftsLessThan1Degree) {
  run(0.5);
  const double yaw0 = yaw();
  setSpeed(1.0);
  run(1.0);
  // Steady speed: mean over the next second, and the worst sample.
  double sum = 0.0, worst = 0.0;
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    sim_.step();
    const double v = physics().baseTwist().linear.head<2>().norm();
    sum += v;
    worst = std::max(worst, std::fabs(v - 1.0));
  }
  const double mean = sum / n;
  // Heading drift over 10 m.
  const Eigen::Vector3d start = physics().basePose().translation();
  while ((physics().basePose().translation() - start).head<2>().norm() < 10.0 && sim_.time() < 30) {
    sim_.step();
  }
  const double drift_deg = std::fabs(yaw() - yaw0) * 180.0 / M_PI;
  std::printf("[figure] (b) 1.0 m/s: mean speed %.5f m/s (error %+.3f%%, worst sample %.3f%%), "
              "heading drift %.4f deg over 10 m\n",
              mean, (mean - 1.0) * 100.0, worst * 100.0, drift_deg);
  EXPECT_NEAR(mean, 1.0, 0.01);
  EXPECT_LT(worst, 0.01);
  EXPECT_LT(drift_deg, 1.0);
}

TEST_F(TianracerSim, SteeringStepSettlesWithin300msWithoutOvershootOrOscillation) {
  run(0.5);
  const int left = physics().jointIndex("left_steering_hinge_joint");
  const double target = 0.4;
  const double t0 = sim_.time();
  setSteer(target, target);
  double peak = 0.0, settled_at = -1.0;
  std::vector<double> trace;
  for (int i = 0; i < 1000; ++i) {
    sim_.step();
    const double q = physics().jointPosition(left);
    trace.push_back(q);
    peak = std::max(peak, q);
  }
  // Settling time: the last time the angle was outside the 2% band.
  for (size_t i = trace.size(); i-- > 0;) {
    if (std::fabs(trace[i] - target) > 0.02 * target) {
      settled_at = (i + 1) * sim_.dt();
      break;
    }
  }
  const double overshoot = (peak - target) / target;
  // No sustained oscillation: over the last half second the angle stays within 0.5% of target.
  double late = 0.0;
  for (size_t i = 500; i < trace.size(); ++i) late = std::max(late, std::fabs(trace[i] - target));
  std::printf("[figure] (c) steering step 0->0.4 rad: settles (2%%) in %.3f s, overshoot %.2f%%, "
              "late amplitude %.5f rad\n",
              settled_at, overshoot * 100.0, late);
  (void)t0;
  EXPECT_LT(settled_at, 0.3);
  EXPECT_LT(overshoot, 0.10);
  EXPECT_LT(late, 0.005 * target);
}

TEST_F(TianracerSim, FullLockAt2MetersPerSecondStaysOnItsWheels) {
  for (double lock : {0.6, -0.6}) {
    sim_.resetSimulation();
    run(0.5);
    setSteer(lock, lock);
    setSpeed(2.0);
    const char* wheels[] = {"left_front_wheel", "right_front_wheel", "left_rear_wheel",
                            "right_rear_wheel"};
    int airborne_steps = 0;
    double max_energy = 0.0, min_up = 1.0, early = 0.0, late = 0.0;
    for (int i = 0; i < 10000; ++i) {
      sim_.step();
      const Eigen::Isometry3d X = physics().basePose();
      ASSERT_TRUE(X.matrix().allFinite()) << "NaN at step " << i;
      min_up = std::min(min_up, X.linear()(2, 2));  // cos(tilt)
      const double ke = physics().kineticEnergy();
      max_energy = std::max(max_energy, ke);
      if (i >= 3000 && i < 5000) early += ke / 2000.0;
      if (i >= 8000) late += ke / 2000.0;
      if (i > 2000) {
        for (const char* w : wheels) {
          if (physics().contactCount(w, 2e-3) == 0) {
            ++airborne_steps;
            break;
          }
        }
      }
    }
    std::printf("[figure] (d) full lock %+.1f rad at 2 m/s, 10 s: steps with a wheel off the "
                "ground %d of 8000, min cos(tilt) %.4f, kinetic energy max %.2f J, mean "
                "3-5 s %.2f J, mean 8-10 s %.2f J\n",
                lock, airborne_steps, min_up, max_energy, early, late);
    EXPECT_EQ(airborne_steps, 0);
    EXPECT_GT(min_up, std::cos(10.0 * M_PI / 180.0));
    // Bounded energy: a steady circle keeps its kinetic energy (no slow blow-up), and no
    // spike: 8.7 kg at 2 m/s is 17.4 J plus wheel spin and yaw; 40 J would be a 50% spike.
    EXPECT_NEAR(late, early, 0.05 * early);
    EXPECT_LT(max_energy, 40.0);
  }
}

TEST_F(TianracerSim, ResetSimulationReturnsToSpawnAndTimeZero) {
  setSpeed(1.0);
  run(1.0);
  ASSERT_GT(physics().basePose().translation().x(), 0.5);
  sim_.resetSimulation();
  EXPECT_EQ(sim_.time(), 0.0);
  EXPECT_NEAR(physics().basePose().translation().x(), 0.0, 1e-12);
  // Controllers restarted: the wheels were commanded back to 0, so the car stays put.
  run(1.0);
  EXPECT_LT(physics().basePose().translation().head<2>().norm(), 1e-3);
}

TEST_F(TianracerSim, NonFiniteCommandsAreRejectedAndNeverReachThePhysics) {
  EXPECT_FALSE(controller("left_rear_wheel_velocity_controller").setCommand(std::nan("")));
  EXPECT_FALSE(controller("left_steering_hinge_position_controller")
                   .setCommand(std::numeric_limits<double>::infinity()));
  run(0.5);
  EXPECT_TRUE(physics().basePose().matrix().allFinite());
  EXPECT_EQ(physics().rejectedCommands(), 0u);
}

TEST(SimulationErrors, ControllerOnAJointWithoutTransmissionNamesTheController) {
  Simulation sim;
  RobotConfig config = test::tianracerAt(Eigen::Vector3d(0, 0, test::kSpawnZ));
  tc::ControllerSpec spec;
  spec.name = "front_wheel_controller";
  spec.type = "velocity_controllers/JointVelocityController";
  spec.params["joint"] = "left_front_wheel_joint";  // rolls freely: no transmission
  config.controllers = {spec};
  try {
    sim.addRobot(std::move(config));
    FAIL() << "expected a ControllerError";
  } catch (const tc::ControllerError& e) {
    EXPECT_NE(std::string(e.what()).find("front_wheel_controller"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("left_front_wheel_joint"), std::string::npos) << e.what();
  }
}

TEST(SimulationErrors, DuplicateRobotNamesAreRefused) {
  Simulation sim;
  RobotConfig a;
  a.name = "car";
  a.model = test::loadTianracer();
  RobotConfig b = a;
  sim.addRobot(std::move(a));
  EXPECT_THROW(sim.addRobot(std::move(b)), ModelError);
}

}  // namespace
}  // namespace tianracer_sim
