// The state messages: ground truth (twist in the child frame), libgazebo_ros_p3d's and the
// drive plugins' odometry (twist as read, their covariances), all filled in place.
#include <cmath>

#include <gtest/gtest.h>

#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {
namespace {

TEST(StateMsgs, GroundTruthGivesThePoseAndTheTwistInTheChildFrame) {
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translation() = Eigen::Vector3d(1, 2, 0.1);
  X_WB.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Twist twist_W;
  twist_W.linear = Eigen::Vector3d(0, 1, 0);   // forward for a car facing +y
  twist_W.angular = Eigen::Vector3d(0, 0, 0.5);
  nav_msgs::Odometry msg;
  toGroundTruth(X_WB, twist_W, ros::Time(3.5), "world", "base_link", &msg);
  EXPECT_EQ(msg.header.frame_id, "world");
  EXPECT_EQ(msg.child_frame_id, "base_link");
  EXPECT_DOUBLE_EQ(msg.header.stamp.toSec(), 3.5);
  EXPECT_DOUBLE_EQ(msg.pose.pose.position.y, 2.0);
  EXPECT_NEAR(msg.pose.pose.orientation.z, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(msg.pose.pose.orientation.w, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(msg.twist.twist.linear.x, 1.0, 1e-12);
  EXPECT_NEAR(msg.twist.twist.linear.y, 0.0, 1e-12);
  EXPECT_NEAR(msg.twist.twist.angular.z, 0.5, 1e-12);
  for (double c : msg.pose.covariance) EXPECT_EQ(c, 0.0);
  // Again into the same message: everything is overwritten.
  toGroundTruth(Eigen::Isometry3d::Identity(), Twist(), ros::Time(4.0), "odom", "b", &msg);
  EXPECT_EQ(msg.header.frame_id, "odom");
  EXPECT_EQ(msg.child_frame_id, "b");
  EXPECT_EQ(msg.twist.twist.linear.x, 0.0);
  EXPECT_EQ(msg.pose.pose.orientation.w, 1.0);
}

TEST(StateMsgs, P3dOdometryKeepsTheWorldTwistAndPutsTheVarianceOnTheDiagonals) {
  P3dReading r;
  r.position = Eigen::Vector3d(1, 0, 0);
  r.linear = Eigen::Vector3d(0, 1, 0);
  r.angular = Eigen::Vector3d(0, 0, 2);
  r.variance = 0.01;
  nav_msgs::Odometry msg;
  toOdometry(r, ros::Time(1.0), "map", "base_link", &msg);
  EXPECT_EQ(msg.header.frame_id, "map");
  EXPECT_EQ(msg.twist.twist.linear.y, 1.0);
  EXPECT_EQ(msg.twist.twist.angular.z, 2.0);
  for (int i = 0; i < 36; ++i) {
    EXPECT_EQ(msg.pose.covariance[i], i % 7 == 0 ? 0.01 : 0.0) << i;
    EXPECT_EQ(msg.twist.covariance[i], i % 7 == 0 ? 0.01 : 0.0) << i;
  }
}

TEST(StateMsgs, DriveOdometryCopiesItsCovariances) {
  DriveOdometry o;
  o.position = Eigen::Vector3d(0, 0, 0.1);
  o.linear = Eigen::Vector3d(0.5, 0, 0);
  for (int i = 0; i < 36; ++i) {
    o.pose_covariance[i] = i;
    o.twist_covariance[i] = -i;
  }
  nav_msgs::Odometry msg;
  toOdometry(o, ros::Time(2.0), "odom", "base_footprint", &msg);
  EXPECT_EQ(msg.child_frame_id, "base_footprint");
  EXPECT_EQ(msg.pose.pose.position.z, 0.1);
  EXPECT_EQ(msg.twist.twist.linear.x, 0.5);
  for (int i = 0; i < 36; ++i) {
    EXPECT_EQ(msg.pose.covariance[i], i);
    EXPECT_EQ(msg.twist.covariance[i], -i);
  }
}

}  // namespace
}  // namespace tianracer_sim
