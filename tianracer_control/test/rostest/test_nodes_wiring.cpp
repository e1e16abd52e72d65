// Wiring of cmd_vel_node and wheel_odometry_node: topics, parameters from robot_description,
// sim time, timeout, bad input, odometry and TF, time jumping back. The test owns /clock: after
// advancing it, the test waits (bounded in wall time) for the nodes' answer to the time it
// stopped at, however late a loaded machine runs them; the clock standing still, no later
// answer can come.
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>

#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>
#include <tf2_msgs/TFMessage.h>

#include "tianracer_control/ackermann.h"

#include "../control_test_support.h"
#include "spin_until.h"

using namespace tianracer_control;  // NOLINT: test file

namespace {

// What the nodes derive from test/data/urdf/ackermann_cylinders.urdf: the seed, hinges to 0.55.
AckermannGeometry urdfGeometry() { return test::seedGeometry(0.55); }

class Wiring : public ::testing::Test {
 protected:
  void SetUp() override {
    clock_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
    cmd_vel_ = nh_.advertise<geometry_msgs::Twist>("/cmd_vel", 10);
    joints_ = nh_.advertise<sensor_msgs::JointState>("/tianracer/joint_states", 10);
    for (const char* c : {"left_steering_hinge_position_controller",
                          "right_steering_hinge_position_controller",
                          "left_rear_wheel_velocity_controller",
                          "right_rear_wheel_velocity_controller"}) {
      const std::string name = c;
      subs_.push_back(nh_.subscribe<std_msgs::Float64>(
          "/tianracer/" + name + "/command", 10,
          [this, name](const std_msgs::Float64::ConstPtr& m) {
            commands_[name] = m->data;
            ++command_count_;
          }));
    }
    odom_sub_ = nh_.subscribe<nav_msgs::Odometry>(
        "/tianracer/odom", 10, [this](const nav_msgs::Odometry::ConstPtr& m) { odom_ = *m; ++odom_count_; });
    tf_sub_ = nh_.subscribe<tf2_msgs::TFMessage>("/tf", 10, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
      for (const auto& t : m->transforms) {
        if (t.header.frame_id == "odom" && t.child_frame_id == "base_link") tf_ = t;
      }
    });
    // Connected (not only registered) both ways: every command topic, odometry and TF.
    ASSERT_TRUE(waitFor([&] {
      bool commands = true;
      for (const ros::Subscriber& s : subs_) commands = commands && s.getNumPublishers() > 0;
      return clock_.getNumSubscribers() >= 3 && cmd_vel_.getNumSubscribers() > 0 &&
             joints_.getNumSubscribers() > 0 && odom_sub_.getNumPublishers() > 0 &&
             tf_sub_.getNumPublishers() > 0 && commands;
    }, kWallTimeout));
  }

  // A bound on a node that stopped, never a measurement.
  static constexpr double kWallTimeout = 60.0;

  bool waitFor(const std::function<bool()>& done, double seconds = kWallTimeout) {
    return test::spinUntil(done, seconds, 0.005);
  }

  void publishClock(double t) {
    rosgraph_msgs::Clock c;
    c.clock = ros::Time(t);
    clock_.publish(c);
    now_ = t;
  }

  // Advances the fake clock in 10 ms steps, calling `each` after every step.
  void advanceTo(double t_end, const std::function<void(double)>& each = {}) {
    while (now_ < t_end - 1e-9) {
      publishClock(std::min(now_ + 0.01, t_end));
      ros::WallDuration(0.004).sleep();
      ros::spinOnce();
      if (each) each(now_);
    }
  }

  // Until cmd_vel_node's latest commands satisfy `done` (the clock standing still at the time
  // they answer).
  bool commandsReach(const std::function<bool()>& done) {
    return waitFor([&] { return command_count_ > 0 && done(); });
  }

  void twist(double v, double w) {
    geometry_msgs::Twist t;
    t.linear.x = v;
    t.angular.z = w;
    cmd_vel_.publish(t);
  }

  void jointStates(double t, double wheel_position, double left_hinge, double right_hinge) {
    sensor_msgs::JointState js;
    js.header.stamp = ros::Time(t);
    js.name = {"left_rear_wheel_joint", "right_rear_wheel_joint", "left_steering_hinge_joint",
               "right_steering_hinge_joint"};
    js.position = {wheel_position, wheel_position, left_hinge, right_hinge};
    js.velocity = {0.0, 0.0, 0.0, 0.0};
    joints_.publish(js);
  }

  ros::NodeHandle nh_;
  ros::Publisher clock_, cmd_vel_, joints_;
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber odom_sub_, tf_sub_;
  std::map<std::string, double> commands_;
  int command_count_ = 0;
  nav_msgs::Odometry odom_;
  int odom_count_ = 0;
  geometry_msgs::TransformStamped tf_;
  double now_ = 0.0;
};

TEST_F(Wiring, CmdVelDrivesTheControllersAndTimesOut) {
  const AckermannGeometry g = urdfGeometry();
  publishClock(1.0);
  advanceTo(1.1);
  // v = 0.5, w = 0.5 (R = 1 m); keep sending at 20 Hz for 0.5 s.
  advanceTo(1.6, [&](double t) {
    if (std::fmod(t + 1e-6, 0.05) < 0.01) twist(0.5, 0.5);
  });
  const double delta = std::atan(g.wheelbase * 0.5 / 0.5);
  commandsReach([&] {
    return std::abs(commands_["left_rear_wheel_velocity_controller"] - 0.5 / 0.032) < 1e-9 &&
           std::abs(commands_["left_steering_hinge_position_controller"] -
                    leftWheelAngle(g, delta)) < 1e-6;
  });
  EXPECT_NEAR(commands_["left_rear_wheel_velocity_controller"], 0.5 / 0.032, 1e-9);
  EXPECT_NEAR(commands_["right_rear_wheel_velocity_controller"], 0.5 / 0.032, 1e-9);
  EXPECT_NEAR(commands_["left_steering_hinge_position_controller"], leftWheelAngle(g, delta), 1e-6);
  EXPECT_NEAR(commands_["right_steering_hinge_position_controller"], rightWheelAngle(g, delta), 1e-6);

  // Bad input: ignored, the node lives and keeps its command.
  twist(std::numeric_limits<double>::quiet_NaN(), 0.0);
  twist(0.5, std::numeric_limits<double>::infinity());
  advanceTo(1.65, [&](double) { twist(0.5, 0.5); });
  EXPECT_NEAR(commands_["left_rear_wheel_velocity_controller"], 0.5 / 0.032, 1e-9);

  // Huge values: clamped to max_speed (2.0) and to the steering limit (0.55 on one hinge).
  advanceTo(1.8, [&](double) { twist(1e9, 1e9); });
  commandsReach([&] {
    return std::abs(commands_["left_rear_wheel_velocity_controller"] - 2.0 / 0.032) < 1e-9 &&
           std::abs(commands_["left_steering_hinge_position_controller"] - 0.55) < 1e-9;
  });
  EXPECT_NEAR(commands_["left_rear_wheel_velocity_controller"], 2.0 / 0.032, 1e-9);
  EXPECT_NEAR(commands_["left_steering_hinge_position_controller"], 0.55, 1e-9);
  EXPECT_LT(commands_["right_steering_hinge_position_controller"], 0.55);

  // Silence: the car stops within the timeout (0.5 s) plus one tick; the steering is held.
  const double held = commands_["left_steering_hinge_position_controller"];
  advanceTo(2.35);
  commandsReach([&] {
    return commands_["left_rear_wheel_velocity_controller"] == 0.0 &&
           commands_["right_rear_wheel_velocity_controller"] == 0.0;
  });
  EXPECT_EQ(commands_["left_rear_wheel_velocity_controller"], 0.0);
  EXPECT_EQ(commands_["right_rear_wheel_velocity_controller"], 0.0);
  EXPECT_EQ(commands_["left_steering_hinge_position_controller"], held);
}

TEST_F(Wiring, OdometryFromJointStatesAndResetOnTimeJump) {
  const AckermannGeometry g = urdfGeometry();
  publishClock(10.0);
  advanceTo(10.02);
  // Straight at 0.5 m/s for 1 s, joint_states at 50 Hz.
  const double t0 = now_;
  advanceTo(t0 + 1.0, [&](double t) {
    if (std::fmod(t + 1e-6, 0.02) < 0.01) jointStates(t, (t - t0) * 0.5 / 0.032, 0.0, 0.0);
  });
  ASSERT_TRUE(waitFor([&] { return odom_count_ > 10; }));
  ASSERT_TRUE(waitFor([&] { return std::abs(odom_.pose.pose.position.x - 0.5) < 0.02; }))
      << odom_.pose.pose.position.x;
  EXPECT_NEAR(odom_.pose.pose.position.y, 0.0, 1e-9);
  EXPECT_NEAR(odom_.twist.twist.linear.x, 0.5, 1e-6);
  EXPECT_EQ(odom_.header.frame_id, "odom");
  EXPECT_EQ(odom_.child_frame_id, "base_link");
  EXPECT_GT(odom_.pose.covariance[0], 0.0);
  EXPECT_EQ(tf_.header.stamp, odom_.header.stamp);
  EXPECT_EQ(tf_.transform.translation.x, odom_.pose.pose.position.x);

  // Turning: hinges at the exact angles of delta = 0.3 give yaw rate v tan(0.3) / L.
  const double t1 = now_;
  const double p1 = (t1 - t0) * 0.5 / 0.032;
  advanceTo(t1 + 0.5, [&](double t) {
    if (std::fmod(t + 1e-6, 0.02) < 0.01) {
      jointStates(t, p1 + (t - t1) * 0.5 / 0.032, leftWheelAngle(g, 0.3), rightWheelAngle(g, 0.3));
    }
  });
  ASSERT_TRUE(waitFor([&] { return odom_.twist.twist.angular.z > 0.1; }));
  EXPECT_NEAR(odom_.twist.twist.angular.z, 0.5 * std::tan(0.3) / g.wheelbase, 1e-6);

  // Sim reset: time back to 0.5 -> odometry back to the origin, stamps from the new timeline.
  publishClock(0.5);
  ros::WallDuration(0.05).sleep();
  jointStates(0.5, 0.0, 0.0, 0.0);
  ASSERT_TRUE(waitFor([&] { return odom_.header.stamp == ros::Time(0.5); }));
  EXPECT_EQ(odom_.pose.pose.position.x, 0.0);
  EXPECT_EQ(odom_.pose.pose.position.y, 0.0);
}

TEST_F(Wiring, OdometryKeepsMessagesAheadOfALaggingClock) {
  // A node starved of CPU while the sim runs faster than real time reads joint_states stamped
  // well ahead of its own /clock. They are the current timeline, not stale: keep them (they
  // used to be dropped as "from before a sim reset" when more than 1 s ahead).
  publishClock(0.6);
  ros::WallDuration(0.05).sleep();
  const double ahead = 2.0, t0 = now_;
  advanceTo(t0 + 0.5, [&](double t) {
    if (std::fmod(t + 1e-6, 0.02) < 0.01) jointStates(t + ahead, (t - t0) * 0.5 / 0.032, 0.0, 0.0);
  });
  ASSERT_TRUE(waitFor([&] { return odom_.header.stamp.toSec() > t0 + ahead + 0.4; }))
      << odom_.header.stamp;
  EXPECT_NEAR(odom_.pose.pose.position.x, 0.5 * (odom_.header.stamp.toSec() - t0 - ahead), 1e-6);
  EXPECT_GT(odom_.pose.pose.position.x, 0.2);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_nodes_wiring");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}
