// SDF's pose convention, shared by the world parser, the XML reader and the sensor blocks.
#ifndef TIANRACER_SIM_COMMON_SDF_POSE_H
#define TIANRACER_SIM_COMMON_SDF_POSE_H

#include <Eigen/Geometry>

namespace tianracer_sim {

/// SDF pose "x y z roll pitch yaw": translation, then R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Isometry3d sdfPose(double x, double y, double z, double roll, double pitch, double yaw);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_SDF_POSE_H
