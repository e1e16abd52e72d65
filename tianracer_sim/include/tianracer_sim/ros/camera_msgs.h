// Camera and depth camera frames -> sensor_msgs (Image, CameraInfo, PointCloud2), as
// gazebo_ros_camera and gazebo_ros_openni_kinect fill them (docs/model_and_sensors.md), except the frame:
// every header carries the sensor's optical frame, "<frameName>_optical_frame"
// (opticalFrameId()), which the node publishes by TF as rpy(-pi/2, 0, -pi/2) from frameName's
// link (CameraConfig::X_LO()). Gazebo stamps the plain link frame, which rviz draws rotated.
#ifndef TIANRACER_SIM_ROS_CAMERA_MSGS_H
#define TIANRACER_SIM_ROS_CAMERA_MSGS_H

#include <ros/time.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/ros/borrowed_msgs.h"

namespace tianracer_sim {

/// rgb8 (R8G8B8) or mono8 (L8), step = W * channels, rows top to bottom.
sensor_msgs::Image toImage(const CameraSensor& camera, const ros::Time& stamp);
/// The depth camera's colour image (openni's rgb/image_raw).
sensor_msgs::Image toImage(const DepthCameraSensor& camera, const ros::Time& stamp);
/// 32FC1 metres along the optical axis, step = 4 W, NaN outside (cutoff, cutoffMax).
sensor_msgs::Image toDepthImage(const DepthCameraSensor& camera, const ros::Time& stamp);
/// D, K, R, P, size and distortion model from makeCameraInfo(); binning 0, full ROI.
sensor_msgs::CameraInfo toCameraInfo(const CameraInfo& info, const ros::Time& stamp);
/// Organized H x W cloud: fields x, y, z, rgb (FLOAT32, offsets 0, 4, 8, 16), point_step 32,
/// row_step 32 W, little-endian; rgb is a float whose bits are 0x00RRGGBB (PCL's
/// PointXYZRGB: bytes 16, 17, 18 = B, G, R); is_dense false when any point is NaN.
sensor_msgs::PointCloud2 toPointCloud2(const DepthCameraSensor& camera, const ros::Time& stamp);

/// The same into existing messages, reusing their buffers (no allocation once warm).
void toImage(const CameraSensor& camera, const ros::Time& stamp, sensor_msgs::Image* msg);
void toImage(const DepthCameraSensor& camera, const ros::Time& stamp, sensor_msgs::Image* msg);
void toDepthImage(const DepthCameraSensor& camera, const ros::Time& stamp, sensor_msgs::Image* msg);
void toCameraInfo(const CameraInfo& info, const ros::Time& stamp, sensor_msgs::CameraInfo* msg);
void toPointCloud2(const DepthCameraSensor& camera, const ros::Time& stamp,
                   sensor_msgs::PointCloud2* msg);

/// The same, the data borrowed from the sensor's buffer instead of copied (borrowed_msgs.h):
/// valid until the sensor renders again. Serialised, each is byte for byte its sensor_msgs
/// counterpart.
void toImage(const CameraSensor& camera, const ros::Time& stamp, BorrowedImage* msg);
void toImage(const DepthCameraSensor& camera, const ros::Time& stamp, BorrowedImage* msg);
void toDepthImage(const DepthCameraSensor& camera, const ros::Time& stamp, BorrowedImage* msg);
void toPointCloud2(const DepthCameraSensor& camera, const ros::Time& stamp,
                   BorrowedPointCloud2* msg);
/// The cloud written by the sensor straight into roscpp's serialisation buffer when published
/// (DepthCameraSensor::writeCloud()): for a sensor rendered with image and depth but without
/// outputs.cloud. Valid until the sensor renders again.
void toPointCloud2Deferred(const DepthCameraSensor& camera, const ros::Time& stamp,
                           BorrowedPointCloud2* msg);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CAMERA_MSGS_H
