#include "tianracer_sim/ros/state_msgs.h"

#include <cmath>

namespace tianracer_sim {

geometry_msgs::Pose toPose(const Eigen::Isometry3d& X) {
  geometry_msgs::Pose p;
  p.position.x = X.translation().x();
  p.position.y = X.translation().y();
  p.position.z = X.translation().z();
  const Eigen::Quaterniond q(X.linear());
  p.orientation.x = q.x();
  p.orientation.y = q.y();
  p.orientation.z = q.z();
  p.orientation.w = q.w();
  return p;
}

geometry_msgs::Twist toTwistMsg(const Twist& twist) {
  geometry_msgs::Twist t;
  t.linear.x = twist.linear.x();
  t.linear.y = twist.linear.y();
  t.linear.z = twist.linear.z();
  t.angular.x = twist.angular.x();
  t.angular.y = twist.angular.y();
  t.angular.z = twist.angular.z();
  return t;
}

nav_msgs::Odometry toGroundTruth(const Eigen::Isometry3d& X_WB, const Twist& twist_W,
                                 const ros::Time& stamp, const std::string& frame,
                                 const std::string& child_frame) {
  nav_msgs::Odometry odom;
  odom.header.stamp = stamp;
  odom.header.frame_id = frame;
  odom.child_frame_id = child_frame;
  odom.pose.pose = toPose(X_WB);
  const Eigen::Matrix3d R_BW = X_WB.linear().transpose();
  Twist body;
  body.linear = R_BW * twist_W.linear;
  body.angular = R_BW * twist_W.angular;
  odom.twist.twist = toTwistMsg(body);
  return odom;
}

bool fromPose(const geometry_msgs::Pose& pose, Eigen::Isometry3d* X) {
  const Eigen::Vector3d t(pose.position.x, pose.position.y, pose.position.z);
  Eigen::Quaterniond q(pose.orientation.w, pose.orientation.x, pose.orientation.y,
                       pose.orientation.z);
  if (!t.allFinite() || !q.coeffs().allFinite() || q.norm() < 1e-9) return false;
  q.normalize();
  X->setIdentity();
  X->linear() = q.toRotationMatrix();
  X->translation() = t;
  return true;
}

bool fromTwistMsg(const geometry_msgs::Twist& msg, Twist* twist) {
  const Eigen::Vector3d v(msg.linear.x, msg.linear.y, msg.linear.z);
  const Eigen::Vector3d w(msg.angular.x, msg.angular.y, msg.angular.z);
  if (!v.allFinite() || !w.allFinite()) return false;
  twist->linear = v;
  twist->angular = w;
  return true;
}

void toOdometry(const P3dReading& r, const ros::Time& stamp, const std::string& frame,
                const std::string& child_frame, nav_msgs::Odometry* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  msg->child_frame_id = child_frame;
  msg->pose.pose.position.x = r.position.x();
  msg->pose.pose.position.y = r.position.y();
  msg->pose.pose.position.z = r.position.z();
  msg->pose.pose.orientation.x = r.orientation.x();
  msg->pose.pose.orientation.y = r.orientation.y();
  msg->pose.pose.orientation.z = r.orientation.z();
  msg->pose.pose.orientation.w = r.orientation.w();
  msg->twist.twist.linear.x = r.linear.x();
  msg->twist.twist.linear.y = r.linear.y();
  msg->twist.twist.linear.z = r.linear.z();
  msg->twist.twist.angular.x = r.angular.x();
  msg->twist.twist.angular.y = r.angular.y();
  msg->twist.twist.angular.z = r.angular.z();
  for (int i = 0; i < 6; ++i) {
    msg->pose.covariance[7 * i] = r.variance;
    msg->twist.covariance[7 * i] = r.variance;
  }
}

void toOdometry(const DriveOdometry& o, const ros::Time& stamp, const std::string& frame,
                const std::string& child_frame, nav_msgs::Odometry* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  msg->child_frame_id = child_frame;
  msg->pose.pose.position.x = o.position.x();
  msg->pose.pose.position.y = o.position.y();
  msg->pose.pose.position.z = o.position.z();
  msg->pose.pose.orientation.x = o.orientation.x();
  msg->pose.pose.orientation.y = o.orientation.y();
  msg->pose.pose.orientation.z = o.orientation.z();
  msg->pose.pose.orientation.w = o.orientation.w();
  msg->twist.twist.linear.x = o.linear.x();
  msg->twist.twist.linear.y = o.linear.y();
  msg->twist.twist.linear.z = o.linear.z();
  msg->twist.twist.angular.x = o.angular.x();
  msg->twist.twist.angular.y = o.angular.y();
  msg->twist.twist.angular.z = o.angular.z();
  for (std::size_t i = 0; i < 36; ++i) {
    msg->pose.covariance[i] = o.pose_covariance[i];
    msg->twist.covariance[i] = o.twist_covariance[i];
  }
}

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& X, const ros::Time& stamp,
                                            const std::string& frame,
                                            const std::string& child_frame) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = frame;
  t.child_frame_id = child_frame;
  t.transform.translation.x = X.translation().x();
  t.transform.translation.y = X.translation().y();
  t.transform.translation.z = X.translation().z();
  const Eigen::Quaterniond q(X.rotation());
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

}  // namespace tianracer_sim
