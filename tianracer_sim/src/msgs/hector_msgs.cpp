#include "tianracer_sim/ros/hector_msgs.h"

#include <cstdint>

#include <tianracer_control/ros/msg_conversion.h>

namespace tianracer_sim {

void toNavSatFix(const HectorGpsReading& r, const std::string& frame, const ros::Time& stamp,
                 sensor_msgs::NavSatFix* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  msg->status.status = static_cast<std::int8_t>(r.status);
  msg->status.service = static_cast<std::uint16_t>(r.service);
  msg->latitude = r.latitude;
  msg->longitude = r.longitude;
  msg->altitude = r.altitude;
  msg->position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN;
  for (int i = 0; i < 9; ++i) msg->position_covariance[i] = r.position_covariance[i];
}

void toGpsVelocity(const HectorGpsReading& r, const std::string& frame, const ros::Time& stamp,
                   geometry_msgs::Vector3Stamped* msg) {
  toVector3Stamped(r.velocity, frame, stamp, msg);
}

void toVector3Stamped(const Eigen::Vector3d& v, const std::string& frame, const ros::Time& stamp,
                      geometry_msgs::Vector3Stamped* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  tianracer_control::toXyzMsg(v, &msg->vector);
}

void toMagneticField(const Eigen::Vector3d& v, const std::string& frame, const ros::Time& stamp,
                     sensor_msgs::MagneticField* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  tianracer_control::toXyzMsg(v, &msg->magnetic_field);
}

void toSonarRange(const RangeReading& r, const std::string& frame, const ros::Time& stamp,
                  sensor_msgs::Range* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame;
  msg->radiation_type = sensor_msgs::Range::ULTRASOUND;
  msg->field_of_view = r.field_of_view;
  msg->min_range = r.min_range;
  msg->max_range = r.max_range;
  msg->range = r.range;
}

}  // namespace tianracer_sim
