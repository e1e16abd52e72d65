// What the sensor publishers share: the sensors' headers (their kinds' functions, which
// TIANRACER_SENSOR_PUBLISHER names) and the camera's optical frame.
#ifndef TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H
#define TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H

#include <memory>

#include "tianracer_sim/ros/plugins/sensor_publisher.h"
#include "tianracer_sim/plugins/bumper/sim_bumper.h"
#include "tianracer_sim/plugins/camera/sim_camera.h"
#include "tianracer_sim/plugins/drives/sim_drive.h"
#include "tianracer_sim/plugins/imu/sim_imu.h"
#include "tianracer_sim/plugins/p3d/sim_p3d.h"
#include "tianracer_sim/plugins/ray/sim_ray.h"

namespace tianracer_sim {

struct CameraConfig;
/// The camera's optical frame (z forward, x right, y down), which its images are stamped
/// with, on static TF under the sensor's link `link` (camera_publisher.cpp).
void sendOpticalFrame(const PublisherSetup& setup, const std::string& link,
                      const CameraConfig& camera);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_ROS_SENSORS_FACTORIES_H
