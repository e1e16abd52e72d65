// The factories of the sensor publishers (one per SensorKind id), for the table in
// sensor_publishers.cpp.
#ifndef TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H
#define TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H

#include <memory>

#include "tianracer_sim/ros/sensors/sensor_publisher.h"

namespace tianracer_sim {

std::unique_ptr<SensorPublisher> makeLidarPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeCameraPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeMultiCameraPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeDepthCameraPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeImuPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeImuPluginPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeP3dPublisher(const SensorSetup& setup);
std::unique_ptr<SensorPublisher> makeBumperPublisher(const SensorSetup& setup);

struct CameraConfig;
/// The camera's optical frame (z forward, x right, y down), which its images are stamped
/// with, on static TF under the sensor's link (camera_publisher.cpp).
void sendOpticalFrame(const SensorSetup& setup, const CameraConfig& camera);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H
