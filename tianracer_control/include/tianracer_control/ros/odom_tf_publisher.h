// The odometry a drive controller's ROS side publishes, as diff_drive_controller,
// ackermann_steering_controller and four_wheel_steering_controller do alike (ros_controllers
// noetic-devel: init()'s setOdomPubFields() and update()'s publications):
//   <controller>/odom  nav_msgs/Odometry odom_frame -> base_frame_id, the pose and twist
//                      covariances on the diagonals (pose_covariance_diagonal,
//                      twist_covariance_diagonal);
//   /tf                tf2_msgs/TFMessage, the same pose odom_frame -> base_frame_id.
// The heading is a yaw quaternion (tf::createQuaternionMsgFromYaw). The messages are kept and
// only their changing fields are written at each publication.
#ifndef TIANRACER_CONTROL_ROS_ODOM_TF_PUBLISHER_H
#define TIANRACER_CONTROL_ROS_ODOM_TF_PUBLISHER_H

#include <string>

#include <geometry_msgs/Quaternion.h>
#include <nav_msgs/Odometry.h>
#include <ros/node_handle.h>
#include <ros/publisher.h>
#include <tf2_msgs/TFMessage.h>

#include "tianracer_control/controllers/cmd_vel_drive_controller.h"

namespace tianracer_control {

/// tf::createQuaternionMsgFromYaw: z = sin(yaw / 2), w = cos(yaw / 2).
geometry_msgs::Quaternion yawQuaternionMsg(double yaw);

class OdomTfPublisher {
 public:
  /// The messages' frames (odom_frame -> p.base_frame_id) and covariances; nothing advertised.
  OdomTfPublisher(const std::string& odom_frame, const CmdVelDriveController::Common& p);
  /// Advertises <controller_nh>/odom and /tf (on root_nh), queue 100 each.
  void advertise(ros::NodeHandle& controller_nh, ros::NodeHandle& root_nh);

  /// Writes the odometry at sim time t: position (x, y), heading, twist (linear x, y; angular z).
  const nav_msgs::Odometry& fillOdom(double t, double x, double y, double heading, double linear_x,
                                     double linear_y, double angular);
  /// Writes the same pose as the /tf transform at sim time t.
  const tf2_msgs::TFMessage& fillTf(double t, double x, double y, double heading);
  void publishOdom(double t, double x, double y, double heading, double linear_x, double linear_y,
                   double angular) {
    odom_pub_.publish(fillOdom(t, x, y, heading, linear_x, linear_y, angular));
  }
  void publishTf(double t, double x, double y, double heading) { tf_pub_.publish(fillTf(t, x, y, heading)); }

 private:
  ros::Publisher odom_pub_, tf_pub_;
  nav_msgs::Odometry odom_;
  tf2_msgs::TFMessage tf_;
};

}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_ROS_ODOM_TF_PUBLISHER_H
