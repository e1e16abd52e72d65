// Conversions of the simulation state to ROS messages (poses, twists, odometry).
#ifndef TIANRACER_SIM_ROS_STATE_MSGS_H
#define TIANRACER_SIM_ROS_STATE_MSGS_H

#include <string>

#include <Eigen/Geometry>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <nav_msgs/Odometry.h>
#include <ros/time.h>

#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/plugins/drives/drives.h"
#include "tianracer_sim/plugins/p3d/p3d.h"

namespace tianracer_sim {

geometry_msgs::Pose toPose(const Eigen::Isometry3d& X);
/// World-frame twist as a geometry_msgs::Twist (linear and angular in the world frame).
geometry_msgs::Twist toTwistMsg(const Twist& twist);

/// The sim's ground truth: pose of `child_frame` in `frame`, twist in the child frame
/// (nav_msgs/Odometry's convention), zero covariance. (libgazebo_ros_p3d's twist is in the
/// world frame: toOdometry() below.)
/// Filled in place: a message kept between calls allocates nothing.
void toGroundTruth(const Eigen::Isometry3d& X_WB, const Twist& twist_W, const ros::Time& stamp,
                   const std::string& frame, const std::string& child_frame,
                   nav_msgs::Odometry* msg);

/// libgazebo_ros_p3d's odometry: the reading as it is (see plugins/p3d/p3d.h), gn^2 on the pose
/// and twist covariance diagonals.
void toOdometry(const P3dReading& reading, const ros::Time& stamp, const std::string& frame,
                const std::string& child_frame, nav_msgs::Odometry* msg);

/// The odometry of a drive plugin (plugins/drives/drives.h) as it fills nav_msgs/Odometry.
void toOdometry(const DriveOdometry& odometry, const ros::Time& stamp, const std::string& frame,
                const std::string& child_frame, nav_msgs::Odometry* msg);
/// X (child_frame in frame) as a TF message.
geometry_msgs::TransformStamped toTransform(const Eigen::Isometry3d& X, const ros::Time& stamp,
                                            const std::string& frame,
                                            const std::string& child_frame);

/// A pose message -> isometry. Returns false (and leaves X untouched) when any value is not
/// finite or the quaternion's norm is 0; the quaternion is normalised otherwise.
bool fromPose(const geometry_msgs::Pose& pose, Eigen::Isometry3d* X);
/// Returns false for a non-finite twist.
bool fromTwistMsg(const geometry_msgs::Twist& msg, Twist* twist);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_STATE_MSGS_H
