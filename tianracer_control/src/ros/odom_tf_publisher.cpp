#include "tianracer_control/ros/odom_tf_publisher.h"

#include <cmath>

namespace tianracer_control {

geometry_msgs::Quaternion yawQuaternionMsg(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw / 2.0);
  q.w = std::cos(yaw / 2.0);
  return q;
}

OdomTfPublisher::OdomTfPublisher(const std::string& odom_frame, const CmdVelDriveController::Common& p) {
  odom_.header.frame_id = odom_frame;
  odom_.child_frame_id = p.base_frame_id;
  for (int i = 0; i < 6; ++i) {
    odom_.pose.covariance[i * 7] = p.pose_covariance_diagonal[i];
    odom_.twist.covariance[i * 7] = p.twist_covariance_diagonal[i];
  }
  tf_.transforms.resize(1);
  tf_.transforms[0].header.frame_id = odom_frame;
  tf_.transforms[0].child_frame_id = p.base_frame_id;
}

void OdomTfPublisher::advertise(ros::NodeHandle& controller_nh, ros::NodeHandle& root_nh) {
  odom_pub_ = controller_nh.advertise<nav_msgs::Odometry>("odom", 100);
  tf_pub_ = root_nh.advertise<tf2_msgs::TFMessage>("/tf", 100);
}

const nav_msgs::Odometry& OdomTfPublisher::fillOdom(double t, double x, double y, double heading,
                                                    double linear_x, double linear_y, double angular) {
  odom_.header.stamp = ros::Time(t);
  odom_.pose.pose.position.x = x;
  odom_.pose.pose.position.y = y;
  odom_.pose.pose.orientation = yawQuaternionMsg(heading);
  odom_.twist.twist.linear.x = linear_x;
  odom_.twist.twist.linear.y = linear_y;
  odom_.twist.twist.angular.z = angular;
  return odom_;
}

const tf2_msgs::TFMessage& OdomTfPublisher::fillTf(double t, double x, double y, double heading) {
  geometry_msgs::TransformStamped& tf = tf_.transforms[0];
  tf.header.stamp = ros::Time(t);
  tf.transform.translation.x = x;
  tf.transform.translation.y = y;
  tf.transform.rotation = yawQuaternionMsg(heading);
  return tf_;
}

}  // namespace tianracer_control
