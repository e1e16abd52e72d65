// Which frame a camera's images are stamped in. Gazebo stamps them with the plugin's
// <frameName> as it is (gazebo_ros_camera_utils.cpp), and most robots' URDFs give the camera a
// link turned z forward for it ("camera_rgb_optical_frame", REP 103's optical frame). But
// where <frameName> is the camera's plain link (x forward), rviz and image_geometry read the
// image turned. So images go out in <frameName> when it is an optical frame at the camera, and
// otherwise in "<frameName>_optical_frame", which the simulator adds on TF.
#ifndef TIANRACER_SIM_PLUGINS_CAMERA_OPTICAL_FRAME_H
#define TIANRACER_SIM_PLUGINS_CAMERA_OPTICAL_FRAME_H

#include <string>

#include <Eigen/Geometry>
#include <urdf_model/model.h>

namespace tianracer_sim {

/// Whether `frame` is a link of the model joined to `link` by fixed joints and turned as the
/// optical frame X_LO of a camera on `link` (z along the view, x right, y down), within
/// 0.01 rad (URDFs write the turn as rpy -1.57 0 -1.57). Where it sits is the URDF's, as in
/// Gazebo.
bool usesOwnOpticalFrame(const urdf::ModelInterface& model, const std::string& link,
                         const Eigen::Isometry3d& X_LO, const std::string& frame);

struct CameraConfig;

/// The decision for a camera as parsed (its link, optical frame and <frameName>, before any
/// tf_prefix), on a robot's URDF; false without one (world models). The simulator stamps its
/// images by it and model_info reports it: one rule for both.
bool usesOwnOpticalFrame(const urdf::ModelInterface* model, const CameraConfig& camera);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_CAMERA_OPTICAL_FRAME_H
