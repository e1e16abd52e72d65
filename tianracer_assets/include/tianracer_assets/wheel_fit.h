// Which wheel mesh is round about its axle, and how big: the one wheel sizing the simulator's
// physics (wheel collision shapes) and tianracer_control (wheel_radius from robot_description)
// share. ROS-free, Eigen only.
#ifndef TIANRACER_ASSETS_WHEEL_FIT_H
#define TIANRACER_ASSETS_WHEEL_FIT_H

#include <vector>

#include <Eigen/Geometry>

namespace tianracer_assets {

/// Wheel fit of a mesh about an axis through the origin of frame B: vertices given in B.
struct WheelFit {
  bool is_wheel = false;
  double radius = 0.0;                               // max distance from the axis
  double width = 0.0;                                // extent along the axis
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // on the axis, mid-width, in B
  double roundness = 0.0;  // (min rim distance) / radius, 1 for a perfect cylinder
};
/// A mesh is a wheel when its outer vertices (distance > 0.9 R) lie within 2% of R from the
/// axis and cover every 30 degree sector around it.
WheelFit fitWheel(const std::vector<Eigen::Vector3d>& vertices_B, const Eigen::Vector3d& axis_B);

}  // namespace tianracer_assets

#endif  // TIANRACER_ASSETS_WHEEL_FIT_H
