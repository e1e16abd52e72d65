#include "tianracer_control/ros/msg_conversion.h"

#include <cmath>

namespace tianracer_control {

namespace {

/// The planar pose's rotation: yaw about z.
Eigen::Quaterniond yawToQuaternion(double yaw) {
  return Eigen::Quaterniond(std::cos(0.5 * yaw), 0.0, 0.0, std::sin(0.5 * yaw));
}

}  // namespace

std_msgs::Float64 toFloat64Msg(double value) {
  std_msgs::Float64 m;
  m.data = value;
  return m;
}

bool fromTwistMsg(const geometry_msgs::Twist& msg, double* linear_x, double* angular_z) {
  if (!std::isfinite(msg.linear.x) || !std::isfinite(msg.angular.z)) return false;
  *linear_x = msg.linear.x;
  *angular_z = msg.angular.z;
  return true;
}

AckermannDriveInput fromAckermannDriveMsg(const ackermann_msgs::AckermannDrive& msg) {
  AckermannDriveInput d;
  d.speed = msg.speed;
  d.steering_angle = msg.steering_angle;
  d.steering_angle_velocity = msg.steering_angle_velocity;
  d.acceleration = msg.acceleration;
  return d;
}

bool fromJointStateMsg(const sensor_msgs::JointState& msg, const AckermannJointNames& joints,
                       AckermannJointSample* sample, std::string* missing) {
  auto index = [&](const std::string& name) -> long {
    for (std::size_t i = 0; i < msg.name.size(); ++i) {
      if (msg.name[i] == name) return static_cast<long>(i);
    }
    return -1;
  };
  const long lh = index(joints.left_hinge), rh = index(joints.right_hinge);
  const long lr = index(joints.left_rear_wheel), rr = index(joints.right_rear_wheel);
  std::string absent;
  for (const auto& [i, name] : {std::pair<long, std::string>{lh, joints.left_hinge},
                                {rh, joints.right_hinge},
                                {lr, joints.left_rear_wheel},
                                {rr, joints.right_rear_wheel}}) {
    if (i < 0) absent += (absent.empty() ? "" : ", ") + name;
  }
  if (!absent.empty()) {
    if (missing) *missing = "joints not in the message: " + absent;
    return false;
  }
  const long np = static_cast<long>(msg.position.size());
  const long nv = static_cast<long>(msg.velocity.size());
  if (lh >= np || rh >= np) {
    if (missing) *missing = "no position for the steering hinges";
    return false;
  }
  sample->left_hinge = msg.position[lh];
  sample->right_hinge = msg.position[rh];
  sample->has_wheel_positions = lr < np && rr < np;
  if (sample->has_wheel_positions) {
    sample->left_rear_position = msg.position[lr];
    sample->right_rear_position = msg.position[rr];
  }
  sample->has_wheel_velocities = lr < nv && rr < nv;
  if (sample->has_wheel_velocities) {
    sample->left_rear_velocity = msg.velocity[lr];
    sample->right_rear_velocity = msg.velocity[rr];
  }
  if (!sample->has_wheel_positions && !sample->has_wheel_velocities) {
    if (missing) *missing = "neither position nor velocity for the rear wheels";
    return false;
  }
  return true;
}

void toQuaternionMsg(const Eigen::Quaterniond& q, geometry_msgs::Quaternion* msg) {
  msg->x = q.x();
  msg->y = q.y();
  msg->z = q.z();
  msg->w = q.w();
}

void fillOdometryMsg(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                     const Eigen::Vector3d& linear, const Eigen::Vector3d& angular,
                     const ros::Time& stamp, const std::string& frame,
                     const std::string& child_frame, nav_msgs::Odometry* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  msg->child_frame_id = child_frame;
  toXyzMsg(position, &msg->pose.pose.position);
  toQuaternionMsg(orientation, &msg->pose.pose.orientation);
  toXyzMsg(linear, &msg->twist.twist.linear);
  toXyzMsg(angular, &msg->twist.twist.angular);
}

geometry_msgs::TransformStamped toTransformMsg(const Eigen::Vector3d& translation,
                                               const Eigen::Quaterniond& rotation,
                                               const ros::Time& stamp, const std::string& frame,
                                               const std::string& child_frame) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = frame;
  t.child_frame_id = child_frame;
  toXyzMsg(translation, &t.transform.translation);
  toQuaternionMsg(rotation, &t.transform.rotation);
  return t;
}

nav_msgs::Odometry toOdometryMsg(const BicycleOdometry& odometry, const ros::Time& stamp,
                                 const std::string& odom_frame, const std::string& base_frame,
                                 const CovarianceDiagonal& pose_covariance,
                                 const CovarianceDiagonal& twist_covariance) {
  nav_msgs::Odometry m;
  fillOdometryMsg(Eigen::Vector3d(odometry.x(), odometry.y(), 0.0),
                  yawToQuaternion(odometry.yaw()),
                  Eigen::Vector3d(odometry.linearVelocity(), odometry.lateralVelocity(), 0.0),
                  Eigen::Vector3d(0.0, 0.0, odometry.angularVelocity()), stamp, odom_frame,
                  base_frame, &m);
  for (int i = 0; i < 6; ++i) {
    m.pose.covariance[i * 6 + i] = pose_covariance[i];
    m.twist.covariance[i * 6 + i] = twist_covariance[i];
  }
  return m;
}

geometry_msgs::TransformStamped toTransformMsg(const BicycleOdometry& odometry,
                                               const ros::Time& stamp,
                                               const std::string& odom_frame,
                                               const std::string& base_frame) {
  return toTransformMsg(Eigen::Vector3d(odometry.x(), odometry.y(), 0.0),
                        yawToQuaternion(odometry.yaw()), stamp, odom_frame, base_frame);
}

}  // namespace tianracer_control
