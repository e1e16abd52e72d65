// camera sensors (gazebo_ros_camera) and depth sensors (gazebo_ros_openni_kinect,
// gazebo_ros_depth_camera). Due frames are decided on the step thread and rendered and
// published on the frame worker (sim/frame_worker.h); camera_infos go out at the step.
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>

#include <tianracer_control/frames.h>

#include "factories.h"
#include "tianracer_sim/render/camera_sensor.h"
#include "tianracer_sim/ros/borrowed_msgs.h"
#include "tianracer_sim/ros/camera_msgs.h"

namespace tianracer_sim {

void sendOpticalFrame(const SensorSetup& setup, const CameraConfig& camera) {
  geometry_msgs::TransformStamped tf;
  tf.header.frame_id = tianracer_control::resolveFrame(setup.tf_prefix, setup.spec->link);
  tf.child_frame_id = camera.opticalFrame();
  const Eigen::Isometry3d X_LO = camera.X_LO();
  const Eigen::Quaterniond q(X_LO.linear());
  tf.transform.translation.x = X_LO.translation().x();
  tf.transform.translation.y = X_LO.translation().y();
  tf.transform.translation.z = X_LO.translation().z();
  tf.transform.rotation.x = q.x();
  tf.transform.rotation.y = q.y();
  tf.transform.rotation.z = q.z();
  tf.transform.rotation.w = q.w();
  setup.static_tf->sendTransform(tf);
}

namespace {

namespace tc = tianracer_control;

/// What both camera kinds share before their own publishers: the link check, the plugin
/// check, the renderer, the frame and topic claim, and the optical frame on TF.
/// Returns false (with a warning) when the sensor publishes nothing.
bool prepareCamera(const SensorSetup& setup, CameraConfig* camera, ros::NodeHandle* cam_nh) {
  if (!camera->has_plugin) {
    setup.warn("robot '" + setup.robot_name + "': camera '" + setup.spec->name +
               "' has no gazebo_ros plugin: nothing to publish, left out");
    return false;
  }
  if (!setup.renderer()) return false;
  camera->frame_name = tc::resolveFrame(setup.tf_prefix, camera->frame_name);
  *cam_nh = ros::NodeHandle(setup.root, resolveTopic(camera->robot_namespace, camera->camera_name));
  setup.claim_topic(cam_nh->getNamespace(),
                    "robot '" + setup.robot_name + "' camera '" + setup.spec->name + "'");

  sendOpticalFrame(setup, *camera);
  return true;
}

/// libgazebo_ros_camera: image + camera_info at the plugin's rate.
class CameraPublisher : public SensorPublisher {
 public:
  CameraPublisher(const SensorSetup& setup, CameraConfig camera, ros::NodeHandle& cam_nh,
                  Renderer& renderer)
      : robot_(setup.robot) {
    if (!camera.noise_seed) camera.noise_seed = static_cast<uint32_t>(setup.seed + 101 + setup.index);
    sensor_ = std::make_unique<CameraSensor>(camera, renderer);
    image_ = cam_nh.advertise<sensor_msgs::Image>(camera.image_topic, 2);
    info_ = cam_nh.advertise<sensor_msgs::CameraInfo>(camera.camera_info_topic, 2);
    schedule_.period = camera.publishRate() > 0.0 ? 1.0 / camera.publishRate() : 0.0;
    stat_ = setup.add_stat(image_.getTopic(), camera.publishRate());
    ROS_INFO("camera '%s' on link %s: %dx%d, hfov %.4g, %g Hz on %s (frame %s)",
             camera.name.c_str(), camera.link.c_str(), camera.width, camera.height,
             camera.horizontal_fov, camera.publishRate(), image_.getTopic().c_str(),
             camera.opticalFrame().c_str());
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    if (!schedule_.due(t)) return;
    SensorStat& stat = host.stat(stat_);
    if (image_.getNumSubscribers() > 0) {
      host.requestFrame({this, host.linkPose(robot_, sensor_->config().link), 0});
      ++stat.count;
      ++stat.renders;
    } else {
      ++stat.skipped;
    }
    if (info_.getNumSubscribers() > 0) {
      toCameraInfo(sensor_->info(), stamp, &info_msg_);
      info_.publish(info_msg_);
    }
  }

  void renderFrame(const Scene& scene, const FrameRequest& request,
                   const ros::Time& stamp) override {
    sensor_->render(scene, request.X_WL);
    toImage(*sensor_, stamp, &image_msg_);
    image_.publish(image_msg_);
  }

  void restart(double t) override { schedule_.restart(t); }

 private:
  std::size_t robot_;
  std::unique_ptr<CameraSensor> sensor_;
  ros::Publisher image_, info_;
  Schedule schedule_;
  BorrowedImage image_msg_;  // the sensor's buffer, serialised by publish() without a copy
  sensor_msgs::CameraInfo info_msg_;
  std::size_t stat_ = 0;
};

/// libgazebo_ros_openni_kinect / libgazebo_ros_depth_camera: rgb, depth and cloud at the
/// sensor rate; both camera_infos at the plugin's updateRate.
class DepthCameraPublisher : public SensorPublisher {
 public:
  enum Output : unsigned { kImage = 1, kDepth = 2, kCloud = 4 };

  DepthCameraPublisher(const SensorSetup& setup, DepthCameraConfig depth,
                       ros::NodeHandle& cam_nh, Renderer& renderer)
      : robot_(setup.robot) {
    CameraConfig& camera = depth.camera;
    if (!camera.noise_seed) camera.noise_seed = static_cast<uint32_t>(setup.seed + 201 + setup.index);
    sensor_ = std::make_unique<DepthCameraSensor>(depth, renderer);
    image_ = cam_nh.advertise<sensor_msgs::Image>(camera.image_topic, 2);
    depth_ = cam_nh.advertise<sensor_msgs::Image>(depth.depth_image_topic, 2);
    cloud_ = cam_nh.advertise<sensor_msgs::PointCloud2>(depth.point_cloud_topic, 2);
    image_info_ = cam_nh.advertise<sensor_msgs::CameraInfo>(camera.camera_info_topic, 2);
    depth_info_ = cam_nh.advertise<sensor_msgs::CameraInfo>(depth.depth_camera_info_topic, 2);
    schedule_.period = camera.update_rate > 0.0 ? 1.0 / camera.update_rate : 0.0;
    info_schedule_.period = camera.publishRate() > 0.0 ? 1.0 / camera.publishRate() : 0.0;
    stat_ = setup.add_stat(image_.getTopic(), camera.update_rate);
    ROS_INFO("depth camera '%s' on link %s: %dx%d, %g Hz images/cloud, %g Hz camera_info under "
             "%s (frame %s)",
             camera.name.c_str(), camera.link.c_str(), camera.width, camera.height,
             camera.update_rate, camera.publishRate(), cam_nh.getNamespace().c_str(),
             camera.opticalFrame().c_str());
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    if (schedule_.due(t)) {
      const unsigned want = (image_.getNumSubscribers() > 0 ? kImage : 0u) |
                            (depth_.getNumSubscribers() > 0 ? kDepth : 0u) |
                            (cloud_.getNumSubscribers() > 0 ? kCloud : 0u);
      SensorStat& stat = host.stat(stat_);
      if (want) {
        host.requestFrame({this, host.linkPose(robot_, sensor_->config().camera.link), want});
        ++stat.count;
        ++stat.renders;
      } else {
        ++stat.skipped;
      }
    }
    if (info_schedule_.due(t) &&
        (image_info_.getNumSubscribers() > 0 || depth_info_.getNumSubscribers() > 0)) {
      toCameraInfo(sensor_->info(), stamp, &info_msg_);
      image_info_.publish(info_msg_);
      depth_info_.publish(info_msg_);
    }
  }

  void renderFrame(const Scene& scene, const FrameRequest& request,
                   const ros::Time& stamp) override {
    const bool image = request.outputs & kImage, depth = request.outputs & kDepth,
               cloud = request.outputs & kCloud;
    // The cloud is not built by the sensor but written by it into the serialisation buffer.
    DepthOutputs render;
    render.image = image || cloud;
    render.depth = depth || cloud;
    render.cloud = false;
    sensor_->render(scene, request.X_WL, render);
    if (image) {
      toImage(*sensor_, stamp, &image_msg_);
      image_.publish(image_msg_);
    }
    if (depth) {
      toDepthImage(*sensor_, stamp, &depth_msg_);
      depth_.publish(depth_msg_);
    }
    if (cloud) {
      toPointCloud2Deferred(*sensor_, stamp, &cloud_msg_);
      cloud_.publish(cloud_msg_);
    }
  }

  void restart(double t) override {
    schedule_.restart(t);
    info_schedule_.restart(t);
  }

 private:
  std::size_t robot_;
  std::unique_ptr<DepthCameraSensor> sensor_;
  ros::Publisher image_, depth_, cloud_, image_info_, depth_info_;
  Schedule schedule_, info_schedule_;
  BorrowedImage image_msg_, depth_msg_;  // borrowed from the sensor
  BorrowedPointCloud2 cloud_msg_;
  sensor_msgs::CameraInfo info_msg_;
  std::size_t stat_ = 0;
};

}  // namespace

std::unique_ptr<SensorPublisher> makeCameraPublisher(const SensorSetup& setup) {
  setup.check_link(setup.spec->link);
  // Parse first: a bad sensor is reported even when there is no renderer.
  CameraConfig camera = parseCameraConfig(*setup.spec, setup.warn);
  ros::NodeHandle cam_nh;
  if (!prepareCamera(setup, &camera, &cam_nh)) return nullptr;
  return std::make_unique<CameraPublisher>(setup, camera, cam_nh, *setup.renderer());
}

std::unique_ptr<SensorPublisher> makeDepthCameraPublisher(const SensorSetup& setup) {
  setup.check_link(setup.spec->link);
  DepthCameraConfig depth = parseDepthCameraConfig(*setup.spec, setup.warn);
  ros::NodeHandle cam_nh;
  if (!prepareCamera(setup, &depth.camera, &cam_nh)) return nullptr;
  return std::make_unique<DepthCameraPublisher>(setup, depth, cam_nh, *setup.renderer());
}

}  // namespace tianracer_sim
