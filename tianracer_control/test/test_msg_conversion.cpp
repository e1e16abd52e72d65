// Message conversions (no roscore needed).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "tianracer_control/ros/msg_conversion.h"
#include "tianracer_control/ros/odom_tf_publisher.h"

using namespace tianracer_control;  // NOLINT: test file

TEST(MsgConversion, Float64) { EXPECT_EQ(toFloat64Msg(1.5).data, 1.5); }

TEST(MsgConversion, TwistRejectsNonFinite) {
  geometry_msgs::Twist t;
  t.linear.x = 1.0;
  t.angular.z = 0.5;
  double v = 0, w = 0;
  ASSERT_TRUE(fromTwistMsg(t, &v, &w));
  EXPECT_EQ(v, 1.0);
  EXPECT_EQ(w, 0.5);
  t.angular.z = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(fromTwistMsg(t, &v, &w));
  EXPECT_EQ(w, 0.5);
  t.angular.z = 0.0;
  t.linear.x = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(fromTwistMsg(t, &v, &w));
}

TEST(MsgConversion, AckermannDriveFieldsAsTheyAre) {
  ackermann_msgs::AckermannDrive m;
  m.speed = 1.5f;
  m.steering_angle = -0.25f;
  m.steering_angle_velocity = 2.0f;
  m.acceleration = 0.5f;
  m.jerk = 9.0f;  // not used
  const AckermannDriveInput d = fromAckermannDriveMsg(m);
  EXPECT_EQ(d.speed, 1.5);
  EXPECT_EQ(d.steering_angle, -0.25);
  EXPECT_EQ(d.steering_angle_velocity, 2.0);
  EXPECT_EQ(d.acceleration, 0.5);
  m.speed = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(fromAckermannDriveMsg(m).speed));  // rejected later, not hidden here
}

TEST(MsgConversion, JointStatePicksJointsByName) {
  sensor_msgs::JointState js;
  js.name = {"left_front_wheel_joint", "right_rear_wheel_joint", "left_steering_hinge_joint",
             "left_rear_wheel_joint", "right_steering_hinge_joint"};
  js.position = {9.0, 2.0, 0.3, 1.0, 0.25};
  js.velocity = {9.0, 20.0, 0.0, 10.0, 0.0};
  AckermannJointSample s;
  std::string missing;
  ASSERT_TRUE(fromJointStateMsg(js, AckermannJointNames(), &s, &missing)) << missing;
  EXPECT_EQ(s.left_rear_position, 1.0);
  EXPECT_EQ(s.right_rear_position, 2.0);
  EXPECT_EQ(s.left_rear_velocity, 10.0);
  EXPECT_EQ(s.right_rear_velocity, 20.0);
  EXPECT_EQ(s.left_hinge, 0.3);
  EXPECT_EQ(s.right_hinge, 0.25);
  EXPECT_TRUE(s.has_wheel_positions);
  EXPECT_TRUE(s.has_wheel_velocities);

  js.velocity.clear();
  ASSERT_TRUE(fromJointStateMsg(js, AckermannJointNames(), &s, &missing));
  EXPECT_FALSE(s.has_wheel_velocities);

  js.name[1] = "rear_right";
  EXPECT_FALSE(fromJointStateMsg(js, AckermannJointNames(), &s, &missing));
  EXPECT_EQ(missing, "joints not in the message: right_rear_wheel_joint");
}

TEST(MsgConversion, OdometryAndTransform) {
  AckermannGeometry g;
  g.rear_axle_x = -0.125;
  BicycleOdometry odo(g);
  odo.integrate(1.0, 0.5, 0.2);
  const CovarianceDiagonal pc{1, 2, 3, 4, 5, 6}, tc{7, 8, 9, 10, 11, 12};
  const nav_msgs::Odometry m = toOdometryMsg(odo, ros::Time(12, 5), "odom", "base_link", pc, tc);
  EXPECT_EQ(m.header.stamp, ros::Time(12, 5));
  EXPECT_EQ(m.header.frame_id, "odom");
  EXPECT_EQ(m.child_frame_id, "base_link");
  EXPECT_EQ(m.pose.pose.position.x, odo.x());
  EXPECT_EQ(m.pose.pose.position.y, odo.y());
  EXPECT_NEAR(m.pose.pose.orientation.z, std::sin(0.05), 1e-15);
  EXPECT_NEAR(m.pose.pose.orientation.w, std::cos(0.05), 1e-15);
  EXPECT_EQ(m.twist.twist.linear.x, 1.0);
  EXPECT_NEAR(m.twist.twist.linear.y, 0.0625, 1e-15);
  EXPECT_EQ(m.twist.twist.angular.z, 0.5);
  EXPECT_EQ(m.pose.covariance[0], 1.0);
  EXPECT_EQ(m.pose.covariance[35], 6.0);
  EXPECT_EQ(m.pose.covariance[1], 0.0);
  EXPECT_EQ(m.twist.covariance[7], 8.0);
  const geometry_msgs::TransformStamped t = toTransformMsg(odo, ros::Time(12, 5), "odom", "base_link");
  EXPECT_EQ(t.transform.translation.x, odo.x());
  EXPECT_EQ(t.transform.rotation.z, m.pose.pose.orientation.z);
  EXPECT_EQ(t.child_frame_id, "base_link");
}

// The drive controllers' odom and /tf (diff drive, ackermann, 4WS): frames and covariance
// diagonals set once, pose, yaw quaternion and twist written per publication.
TEST(MsgConversion, DriveControllerOdomAndTf) {
  CmdVelDriveController::Common p;
  p.base_frame_id = "chassis";
  p.pose_covariance_diagonal = {1, 2, 3, 4, 5, 6};
  p.twist_covariance_diagonal = {7, 8, 9, 10, 11, 12};
  OdomTfPublisher pub("odom_a", p);
  const nav_msgs::Odometry& m = pub.fillOdom(2.5, 1.0, -2.0, 0.6, 0.3, -0.1, 0.4);
  EXPECT_EQ(m.header.stamp, ros::Time(2.5));
  EXPECT_EQ(m.header.frame_id, "odom_a");
  EXPECT_EQ(m.child_frame_id, "chassis");
  EXPECT_EQ(m.pose.pose.position.x, 1.0);
  EXPECT_EQ(m.pose.pose.position.y, -2.0);
  EXPECT_EQ(m.pose.pose.position.z, 0.0);
  EXPECT_EQ(m.pose.pose.orientation.x, 0.0);
  EXPECT_EQ(m.pose.pose.orientation.y, 0.0);
  EXPECT_EQ(m.pose.pose.orientation.z, std::sin(0.3));
  EXPECT_EQ(m.pose.pose.orientation.w, std::cos(0.3));
  EXPECT_EQ(m.twist.twist.linear.x, 0.3);
  EXPECT_EQ(m.twist.twist.linear.y, -0.1);
  EXPECT_EQ(m.twist.twist.angular.z, 0.4);
  for (int i = 0; i < 36; ++i) {
    EXPECT_EQ(m.pose.covariance[i], i % 7 == 0 ? 1.0 + i / 7 : 0.0) << i;
    EXPECT_EQ(m.twist.covariance[i], i % 7 == 0 ? 7.0 + i / 7 : 0.0) << i;
  }
  const tf2_msgs::TFMessage& tf = pub.fillTf(3.0, 4.0, 5.0, -1.0);
  ASSERT_EQ(tf.transforms.size(), 1u);
  const geometry_msgs::TransformStamped& t = tf.transforms[0];
  EXPECT_EQ(t.header.stamp, ros::Time(3.0));
  EXPECT_EQ(t.header.frame_id, "odom_a");
  EXPECT_EQ(t.child_frame_id, "chassis");
  EXPECT_EQ(t.transform.translation.x, 4.0);
  EXPECT_EQ(t.transform.translation.y, 5.0);
  EXPECT_EQ(t.transform.translation.z, 0.0);
  EXPECT_EQ(t.transform.rotation.z, std::sin(-0.5));
  EXPECT_EQ(t.transform.rotation.w, std::cos(-0.5));
  // The next odometry keeps the frames and covariances.
  const nav_msgs::Odometry& n = pub.fillOdom(2.6, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
  EXPECT_EQ(n.header.frame_id, "odom_a");
  EXPECT_EQ(n.pose.covariance[35], 6.0);
  EXPECT_EQ(n.pose.pose.orientation.w, 1.0);
}
