// camera sensors (gazebo_ros_camera) and depth sensors (gazebo_ros_openni_kinect,
// gazebo_ros_depth_camera). Frames are rendered by the Simulator's frame worker and published
// from there (sim/frame_worker.h); camera_infos go out at the step.
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Empty.h>

#include <tianracer_control/naming.h>
#include <tianracer_control/ros/msg_conversion.h>

#include "factories.h"
#include "tianracer_sim/ros/borrowed_msgs.h"
#include "tianracer_sim/ros/camera_msgs.h"

namespace tianracer_sim {

void sendOpticalFrame(const PublisherSetup& setup, const std::string& link,
                      const CameraConfig& camera) {
  std::string parent = tianracer_control::resolveFrame(setup.tf_prefix, link);
  Eigen::Isometry3d X_LO = camera.X_LO();
  if (setup.world_model) {
    // Nothing puts a world model's links on TF (neither does Gazebo): the optical frame hangs
    // from the frameName the plugin names (the sensor's frame), which the user may place.
    parent = camera.frame_name;
    X_LO = camera.X_LS.inverse() * X_LO;
  }
  const geometry_msgs::TransformStamped tf = tianracer_control::toTransformMsg(
      X_LO.translation(), Eigen::Quaterniond(X_LO.linear()), ros::Time(), parent,
      camera.opticalFrame());
  setup.static_tf->sendTransform(tf);
}

namespace {

/// What both camera kinds share before their own publishers: the topic namespace claim and
/// the optical frame on TF.
ros::NodeHandle prepareCamera(const PublisherSetup& setup, const SimSensor& sensor,
                              const CameraConfig& camera) {
  ros::NodeHandle cam_nh(setup.root, resolveTopic(camera.robot_namespace, camera.camera_name));
  setup.claim_topic(cam_nh.getNamespace(),
                    setup.owner() + " camera '" + sensor.name() + "'");
  if (!camera.frame_is_optical) sendOpticalFrame(setup, sensor.link().link, camera);
  return cam_nh;
}

/// libgazebo_ros_camera: image + camera_info at the plugin's rate.
class CameraPublisher : public SensorListener {
 public:
  CameraPublisher(SimCamera& sensor, const PublisherSetup& setup) {
    const CameraConfig& camera = sensor.camera().config();
    ros::NodeHandle cam_nh = prepareCamera(setup, sensor, camera);
    image_ = cam_nh.advertise<sensor_msgs::Image>(camera.image_topic, 2);
    info_ = cam_nh.advertise<sensor_msgs::CameraInfo>(camera.camera_info_topic, 2);
    sensor.stat().name = image_.getTopic();
    if (camera.triggered) {
      // Upstream's queue holds 1 but is drained every millisecond by a thread of its own; ours
      // is drained between steps, so it keeps a few triggers rather than drop one.
      SimCamera* target = &sensor;
      trigger_ = cam_nh.subscribe<std_msgs::Empty>(
          camera.trigger_topic, 10, [target](const std_msgs::Empty::ConstPtr&) { target->trigger(); });
      ROS_INFO("camera '%s' is triggered: one image per message on %s", camera.name.c_str(),
               trigger_.getTopic().c_str());
    }
    ROS_INFO("camera '%s' on link %s: %dx%d, hfov %.4g, %g Hz on %s (frame %s)",
             camera.name.c_str(), camera.link.c_str(), camera.width, camera.height,
             camera.horizontal_fov, camera.publishRate(), image_.getTopic().c_str(),
             camera.opticalFrame().c_str());
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs) override {
    return (image_.getNumSubscribers() > 0 ? SimCamera::kImage : 0) |
           (info_.getNumSubscribers() > 0 ? SimCamera::kInfo : 0);
  }

  void onOutputs(const SimSensor& s, SensorOutputs outputs, double t) override {
    const CameraSensor& camera = static_cast<const SimCamera&>(s).camera();
    const ros::Time stamp(t);
    if (outputs & SimCamera::kImage) {  // on the frame worker
      toImage(camera, stamp, &image_msg_);
      image_.publish(image_msg_);
    }
    if (outputs & SimCamera::kInfo) {
      toCameraInfo(camera.info(), stamp, &info_msg_);
      info_.publish(info_msg_);
    }
  }

 private:
  ros::Publisher image_, info_;
  ros::Subscriber trigger_;
  BorrowedImage image_msg_;  // the sensor's buffer, serialised by publish() without a copy
  sensor_msgs::CameraInfo info_msg_;
};

/// libgazebo_ros_openni_kinect / libgazebo_ros_depth_camera: rgb, depth and cloud at the
/// sensor rate; both camera_infos at the plugin's updateRate.
class DepthCameraPublisher : public SensorListener {
 public:
  DepthCameraPublisher(SimDepthCamera& sensor, const PublisherSetup& setup) {
    const DepthCameraConfig& depth = sensor.camera().config();
    const CameraConfig& camera = depth.camera;
    ros::NodeHandle cam_nh = prepareCamera(setup, sensor, camera);
    image_ = cam_nh.advertise<sensor_msgs::Image>(camera.image_topic, 2);
    depth_ = cam_nh.advertise<sensor_msgs::Image>(depth.depth_image_topic, 2);
    cloud_ = cam_nh.advertise<sensor_msgs::PointCloud2>(depth.point_cloud_topic, 2);
    image_info_ = cam_nh.advertise<sensor_msgs::CameraInfo>(camera.camera_info_topic, 2);
    depth_info_ = cam_nh.advertise<sensor_msgs::CameraInfo>(depth.depth_camera_info_topic, 2);
    sensor.stat().name = image_.getTopic();
    ROS_INFO("depth camera '%s' on link %s: %dx%d, %g Hz images/cloud, %g Hz camera_info under "
             "%s (frame %s)",
             camera.name.c_str(), camera.link.c_str(), camera.width, camera.height,
             camera.update_rate, camera.publishRate(), cam_nh.getNamespace().c_str(),
             camera.opticalFrame().c_str());
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs) override {
    return (image_.getNumSubscribers() > 0 ? SimDepthCamera::kImage : 0) |
           (depth_.getNumSubscribers() > 0 ? SimDepthCamera::kDepth : 0) |
           (cloud_.getNumSubscribers() > 0 ? SimDepthCamera::kCloud : 0) |
           (image_info_.getNumSubscribers() > 0 || depth_info_.getNumSubscribers() > 0
                ? SimDepthCamera::kInfo
                : 0);
  }

  void onOutputs(const SimSensor& s, SensorOutputs outputs, double t) override {
    const DepthCameraSensor& camera = static_cast<const SimDepthCamera&>(s).camera();
    const ros::Time stamp(t);
    // Rendered outputs arrive on the frame worker, camera_info at the step.
    if (outputs & SimDepthCamera::kImage) {
      toImage(camera, stamp, &image_msg_);
      image_.publish(image_msg_);
    }
    if (outputs & SimDepthCamera::kDepth) {
      toDepthImage(camera, stamp, &depth_msg_);
      depth_.publish(depth_msg_);
    }
    if (outputs & SimDepthCamera::kCloud) {
      // The cloud is written by the sensor straight into the serialisation buffer.
      toPointCloud2Deferred(camera, stamp, &cloud_msg_);
      cloud_.publish(cloud_msg_);
    }
    if (outputs & SimDepthCamera::kInfo) {
      toCameraInfo(camera.info(), stamp, &info_msg_);
      image_info_.publish(info_msg_);
      depth_info_.publish(info_msg_);
    }
  }

 private:
  ros::Publisher image_, depth_, cloud_, image_info_, depth_info_;
  BorrowedImage image_msg_, depth_msg_;  // borrowed from the sensor
  BorrowedPointCloud2 cloud_msg_;
  sensor_msgs::CameraInfo info_msg_;
};

}  // namespace

std::unique_ptr<SensorListener> makeCameraPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<CameraPublisher>(static_cast<SimCamera&>(sensor), setup);
}

std::unique_ptr<SensorListener> makeDepthCameraPublisher(SimSensor& sensor,
                                                         const PublisherSetup& setup) {
  return std::make_unique<DepthCameraPublisher>(static_cast<SimDepthCamera&>(sensor), setup);
}

TIANRACER_SENSOR_PUBLISHER(cameraKind, makeCameraPublisher);
TIANRACER_SENSOR_PUBLISHER(depthCameraKind, makeDepthCameraPublisher);

}  // namespace tianracer_sim
