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

namespace {

/// Header, pose and twist of an odometry message (the covariances are the caller's).
void fillOdometry(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                  const Eigen::Vector3d& linear, const Eigen::Vector3d& angular,
                  const ros::Time& stamp, const std::string& frame,
                  const std::string& child_frame, nav_msgs::Odometry* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  msg->child_frame_id = child_frame;
  msg->pose.pose.position.x = position.x();
  msg->pose.pose.position.y = position.y();
  msg->pose.pose.position.z = position.z();
  msg->pose.pose.orientation.x = orientation.x();
  msg->pose.pose.orientation.y = orientation.y();
  msg->pose.pose.orientation.z = orientation.z();
  msg->pose.pose.orientation.w = orientation.w();
  msg->twist.twist.linear.x = linear.x();
  msg->twist.twist.linear.y = linear.y();
  msg->twist.twist.linear.z = linear.z();
  msg->twist.twist.angular.x = angular.x();
  msg->twist.twist.angular.y = angular.y();
  msg->twist.twist.angular.z = angular.z();
}

}  // namespace

void toGroundTruth(const Eigen::Isometry3d& X_WB, const Twist& twist_W, const ros::Time& stamp,
                   const std::string& frame, const std::string& child_frame,
                   nav_msgs::Odometry* msg) {
  const Eigen::Matrix3d R_BW = X_WB.linear().transpose();
  fillOdometry(X_WB.translation(), Eigen::Quaterniond(X_WB.linear()), R_BW * twist_W.linear,
               R_BW * twist_W.angular, stamp, frame, child_frame, msg);
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
  fillOdometry(r.position, r.orientation, r.linear, r.angular, stamp, frame, child_frame, msg);
  for (int i = 0; i < 6; ++i) {
    msg->pose.covariance[7 * i] = r.variance;
    msg->twist.covariance[7 * i] = r.variance;
  }
}

void toOdometry(const DriveOdometry& o, const ros::Time& stamp, const std::string& frame,
                const std::string& child_frame, nav_msgs::Odometry* msg) {
  fillOdometry(o.position, o.orientation, o.linear, o.angular, stamp, frame, child_frame, msg);
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
