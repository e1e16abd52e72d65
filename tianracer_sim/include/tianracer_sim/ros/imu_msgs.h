// ImuSensor readings -> sensor_msgs/Imu.
#ifndef TIANRACER_SIM_ROS_IMU_MSGS_H
#define TIANRACER_SIM_ROS_IMU_MSGS_H

#include <ros/time.h>
#include <sensor_msgs/Imu.h>

#include "tianracer_sim/plugins/imu/imu_sensor.h"

namespace tianracer_sim {

/// header.stamp = stamp (frame_id is left as set); orientation, rates, accelerations and the
/// three covariances from the reading.
void toImu(const ImuReading& reading, const ros::Time& stamp, sensor_msgs::Imu* msg);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_IMU_MSGS_H
