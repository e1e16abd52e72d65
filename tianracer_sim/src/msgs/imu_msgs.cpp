#include "tianracer_sim/ros/imu_msgs.h"

#include <tianracer_control/ros/msg_conversion.h>

namespace tianracer_sim {

void toImu(const ImuReading& r, const ros::Time& stamp, sensor_msgs::Imu* msg) {
  msg->header.stamp = stamp;
  msg->orientation.x = r.orientation_xyzw[0];
  msg->orientation.y = r.orientation_xyzw[1];
  msg->orientation.z = r.orientation_xyzw[2];
  msg->orientation.w = r.orientation_xyzw[3];
  tianracer_control::toXyzMsg(r.angular_velocity, &msg->angular_velocity);
  tianracer_control::toXyzMsg(r.linear_acceleration, &msg->linear_acceleration);
  for (int i = 0; i < 9; ++i) {
    msg->orientation_covariance[i] = r.orientation_covariance[i];
    msg->angular_velocity_covariance[i] = r.angular_velocity_covariance[i];
    msg->linear_acceleration_covariance[i] = r.linear_acceleration_covariance[i];
  }
}

}  // namespace tianracer_sim
