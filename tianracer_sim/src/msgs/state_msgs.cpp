#include "tianracer_sim/ros/state_msgs.h"

#include <cmath>

#include <tianracer_control/ros/msg_conversion.h>

namespace tianracer_sim {

namespace tc = tianracer_control;

geometry_msgs::Pose toPose(const Eigen::Isometry3d& X) {
  geometry_msgs::Pose p;
  tc::toXyzMsg(X.translation(), &p.position);
  tc::toQuaternionMsg(Eigen::Quaterniond(X.linear()), &p.orientation);
  return p;
}

geometry_msgs::Twist toTwistMsg(const Twist& twist) {
  geometry_msgs::Twist t;
  tc::toXyzMsg(twist.linear, &t.linear);
  tc::toXyzMsg(twist.angular, &t.angular);
  return t;
}

void toGroundTruth(const Eigen::Isometry3d& X_WB, const Twist& twist_W, const ros::Time& stamp,
                   const std::string& frame, const std::string& child_frame,
                   nav_msgs::Odometry* msg) {
  const Eigen::Matrix3d R_BW = X_WB.linear().transpose();
  tc::fillOdometryMsg(X_WB.translation(), Eigen::Quaterniond(X_WB.linear()),
                      R_BW * twist_W.linear, R_BW * twist_W.angular, stamp, frame, child_frame,
                      msg);
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
  tc::fillOdometryMsg(r.position, r.orientation, r.linear, r.angular, stamp, frame, child_frame,
                      msg);
  for (int i = 0; i < 6; ++i) {
    msg->pose.covariance[7 * i] = r.variance;
    msg->twist.covariance[7 * i] = r.variance;
  }
}

void toOdometry(const DriveOdometry& o, const ros::Time& stamp, const std::string& frame,
                const std::string& child_frame, nav_msgs::Odometry* msg) {
  tc::fillOdometryMsg(o.position, o.orientation, o.linear, o.angular, stamp, frame, child_frame,
                      msg);
  for (std::size_t i = 0; i < 36; ++i) {
    msg->pose.covariance[i] = o.pose_covariance[i];
    msg->twist.covariance[i] = o.twist_covariance[i];
  }
}

geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& X, const ros::Time& stamp,
                                            const std::string& frame,
                                            const std::string& child_frame) {
  return tc::toTransformMsg(X.translation(), Eigen::Quaterniond(X.rotation()), stamp, frame,
                            child_frame);
}

}  // namespace tianracer_sim
