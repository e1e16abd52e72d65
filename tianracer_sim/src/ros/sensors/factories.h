// The factories of the sensor publishers (one per SensorKind id), for the table in
// sensor_publishers.cpp.
#ifndef TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H
#define TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H

#include <memory>

#include "tianracer_sim/ros/sensors/sensor_publisher.h"
#include "tianracer_sim/sensors/bumper/sim_bumper.h"
#include "tianracer_sim/sensors/camera/sim_camera.h"
#include "tianracer_sim/sensors/drives/sim_drive.h"
#include "tianracer_sim/sensors/imu/sim_imu.h"
#include "tianracer_sim/sensors/p3d/sim_p3d.h"
#include "tianracer_sim/sensors/ray/sim_ray.h"

namespace tianracer_sim {

std::unique_ptr<SensorListener> makeLidarPublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeCameraPublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeMultiCameraPublisher(SimSensor& sensor,
                                                         const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeDepthCameraPublisher(SimSensor& sensor,
                                                         const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeImuPublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeP3dPublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeBumperPublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeRangePublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeBlockLaserPublisher(SimSensor& sensor,
                                                        const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeDrivePublisher(SimSensor& sensor, const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeHectorImuPublisher(SimSensor& sensor,
                                                       const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeHectorGpsPublisher(SimSensor& sensor,
                                                       const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeHectorMagneticPublisher(SimSensor& sensor,
                                                            const PublisherSetup& setup);
std::unique_ptr<SensorListener> makeHectorSonarPublisher(SimSensor& sensor,
                                                         const PublisherSetup& setup);

struct CameraConfig;
/// The camera's optical frame (z forward, x right, y down), which its images are stamped
/// with, on static TF under the sensor's link `link` (camera_publisher.cpp).
void sendOpticalFrame(const PublisherSetup& setup, const std::string& link,
                      const CameraConfig& camera);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H
