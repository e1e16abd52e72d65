// Every ROS message conversion of tianracer_control, in one place (core types never include
// *_msgs). Plain functions, tested without a roscore.
#ifndef TIANRACER_CONTROL_ROS_MSG_CONVERSION_H
#define TIANRACER_CONTROL_ROS_MSG_CONVERSION_H

#include <array>
#include <string>

#include <Eigen/Geometry>
#include <ackermann_msgs/AckermannDrive.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include "tianracer_control/cmd_vel.h"
#include "tianracer_control/odometry.h"
#include "tianracer_control/urdf_geometry.h"

namespace tianracer_control {

std_msgs::Float64 toFloat64Msg(double value);

/// linear.x and angular.z; false (outputs untouched) if either is NaN/inf.
bool fromTwistMsg(const geometry_msgs::Twist& msg, double* linear_x, double* angular_z);

/// The fields as they are (float32 widened); validation is CmdVelProcessor::setAckermann's.
AckermannDriveInput fromAckermannDriveMsg(const ackermann_msgs::AckermannDrive& msg);

/// The four joints the odometry needs, picked out of a JointState by name.
struct AckermannJointSample {
  double left_rear_position = 0.0, right_rear_position = 0.0;
  double left_rear_velocity = 0.0, right_rear_velocity = 0.0;
  double left_hinge = 0.0, right_hinge = 0.0;
  bool has_wheel_positions = false;   // position[] long enough for the rear wheels
  bool has_wheel_velocities = false;  // velocity[] long enough for the rear wheels
};

/// False when a joint is not in msg.name or the hinges have no position; `missing` then names
/// what is missing.
bool fromJointStateMsg(const sensor_msgs::JointState& msg, const AckermannJointNames& joints,
                       AckermannJointSample* sample, std::string* missing);

/// Diagonals of the 6x6 covariances (x, y, z, roll, pitch, yaw), row-major in the message.
using CovarianceDiagonal = std::array<double, 6>;

/// An Eigen vector into a message with fields x, y, z (geometry_msgs Point, Vector3).
template <class XyzMsg>
void toXyzMsg(const Eigen::Vector3d& v, XyzMsg* msg) {
  msg->x = v.x();
  msg->y = v.y();
  msg->z = v.z();
}

/// q's coefficients as they are (not normalised).
void toQuaternionMsg(const Eigen::Quaterniond& q, geometry_msgs::Quaternion* msg);

/// Header, frames, pose (position, orientation of child_frame in frame) and twist (linear,
/// angular) of an odometry message; the covariances are the caller's. The tianracer_sim
/// simulator's odometry messages are filled here too.
void fillOdometryMsg(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                     const Eigen::Vector3d& linear, const Eigen::Vector3d& angular,
                     const ros::Time& stamp, const std::string& frame,
                     const std::string& child_frame, nav_msgs::Odometry* msg);

/// The pose (translation, rotation) of child_frame in frame as TF.
geometry_msgs::TransformStamped toTransformMsg(const Eigen::Vector3d& translation,
                                               const Eigen::Quaterniond& rotation,
                                               const ros::Time& stamp, const std::string& frame,
                                               const std::string& child_frame);

/// Pose of base_frame in odom_frame and its twist in base_frame.
nav_msgs::Odometry toOdometryMsg(const BicycleOdometry& odometry, const ros::Time& stamp,
                                 const std::string& odom_frame, const std::string& base_frame,
                                 const CovarianceDiagonal& pose_covariance,
                                 const CovarianceDiagonal& twist_covariance);

/// The same pose as TF odom_frame -> base_frame.
geometry_msgs::TransformStamped toTransformMsg(const BicycleOdometry& odometry,
                                               const ros::Time& stamp,
                                               const std::string& odom_frame,
                                               const std::string& base_frame);

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_MSG_CONVERSION_H
