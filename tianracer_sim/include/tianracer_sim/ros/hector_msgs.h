// hector_gazebo_plugins' readings (plugins/hector/) -> their messages, filled as upstream fills
// them (gazebo_ros_imu.cpp, gazebo_ros_gps.cpp, gazebo_ros_magnetic.cpp, gazebo_ros_sonar.cpp).
#ifndef TIANRACER_SIM_ROS_HECTOR_MSGS_H
#define TIANRACER_SIM_ROS_HECTOR_MSGS_H

#include <string>

#include <geometry_msgs/Vector3Stamped.h>
#include <ros/time.h>
#include <sensor_msgs/MagneticField.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/Range.h>

#include "tianracer_sim/plugins/hector/hector_gps.h"
#include "tianracer_sim/plugins/ray/ray_plugins.h"

namespace tianracer_sim {

/// NavSatFix: stamp, frame, latitude, longitude, altitude, status and service,
/// COVARIANCE_TYPE_DIAGONAL_KNOWN with the reading's diagonal.
void toNavSatFix(const HectorGpsReading& reading, const std::string& frame, const ros::Time& stamp,
                 sensor_msgs::NavSatFix* msg);
/// The GPS velocity (Vector3Stamped), in the same frame.
void toGpsVelocity(const HectorGpsReading& reading, const std::string& frame,
                   const ros::Time& stamp, geometry_msgs::Vector3Stamped* msg);
/// The magnetometer's field as Vector3Stamped, or as MagneticField (covariance 0: unknown).
void toVector3Stamped(const Eigen::Vector3d& v, const std::string& frame, const ros::Time& stamp,
                      geometry_msgs::Vector3Stamped* msg);
void toMagneticField(const Eigen::Vector3d& v, const std::string& frame, const ros::Time& stamp,
                     sensor_msgs::MagneticField* msg);
/// The sonar's Range (ULTRASOUND).
void toSonarRange(const RangeReading& reading, const std::string& frame, const ros::Time& stamp,
                  sensor_msgs::Range* msg);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_HECTOR_MSGS_H
