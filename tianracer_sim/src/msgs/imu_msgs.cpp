#include "tianracer_sim/ros/imu_msgs.h"

namespace tianracer_sim {

void toImu(const ImuReading& r, const ros::Time& stamp, sensor_msgs::Imu* msg) {
  msg->header.stamp = stamp;
  msg->orientation.x = r.orientation_xyzw[0];
  msg->orientation.y = r.orientation_xyzw[1];
  msg->orientation.z = r.orientation_xyzw[2];
  msg->orientation.w = r.orientation_xyzw[3];
  msg->angular_velocity.x = r.angular_velocity.x();
  msg->angular_velocity.y = r.angular_velocity.y();
  msg->angular_velocity.z = r.angular_velocity.z();
  msg->linear_acceleration.x = r.linear_acceleration.x();
  msg->linear_acceleration.y = r.linear_acceleration.y();
  msg->linear_acceleration.z = r.linear_acceleration.z();
  for (int i = 0; i < 9; ++i) {
    msg->orientation_covariance[i] = r.orientation_covariance[i];
    msg->angular_velocity_covariance[i] = r.angular_velocity_covariance[i];
    msg->linear_acceleration_covariance[i] = r.linear_acceleration_covariance[i];
  }
}

}  // namespace tianracer_sim
