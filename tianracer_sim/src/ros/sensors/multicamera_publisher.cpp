// multicamera sensors (gazebo_ros_multicamera, e.g. a stereo pair): every camera renders and
// publishes as a camera sensor does, all on one schedule (one render per camera per period,
// only for cameras whose image has a subscriber). Frames are rendered on the frame worker;
// camera_infos go out at the step.
#include <set>

#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <tianracer_control/frames.h>

#include "factories.h"
#include "tianracer_sim/render/camera_sensor.h"
#include "tianracer_sim/render/multicamera_config.h"
#include "tianracer_sim/ros/borrowed_msgs.h"
#include "tianracer_sim/ros/camera_msgs.h"

namespace tianracer_sim {
namespace {

namespace tc = tianracer_control;

// One bit a camera in FrameRequest::outputs.
constexpr std::size_t kMaxCameras = 32;

class MultiCameraPublisher : public SensorPublisher {
 public:
  MultiCameraPublisher(const SensorSetup& setup, MultiCameraConfig config, Renderer& renderer)
      : robot_(setup.robot), link_(config.link) {
    const std::string owner =
        "robot '" + setup.robot_name + "' multicamera '" + setup.spec->name + "'";
    std::set<std::string> frames_sent;
    cameras_.resize(config.cameras.size());
    for (std::size_t i = 0; i < config.cameras.size(); ++i) {
      CameraConfig& c = config.cameras[i];
      c.noise_seed ^= static_cast<uint32_t>(setup.seed);
      if (c.noise_seed == 0) c.noise_seed = 1;
      c.frame_name = tc::resolveFrame(setup.tf_prefix, c.frame_name);
      ros::NodeHandle nh(setup.root, resolveTopic(c.robot_namespace, c.camera_name));
      setup.claim_topic(nh.getNamespace(), owner + " camera '" + c.name + "'");
      // One optical frame per frame name: cameras sharing a frameName are stamped with the
      // first one's frame, as Gazebo stamps them; P[3] carries the right camera's offset.
      if (frames_sent.insert(c.opticalFrame()).second) sendOpticalFrame(setup, c);
      Camera& cam = cameras_[i];
      cam.sensor = std::make_unique<CameraSensor>(c, renderer);
      cam.image = nh.advertise<sensor_msgs::Image>(c.image_topic, 2);
      cam.info = nh.advertise<sensor_msgs::CameraInfo>(c.camera_info_topic, 2);
      ROS_INFO("multicamera '%s' camera '%s' on link %s: %dx%d %s, hfov %.4g, %g Hz on %s "
               "(frame %s, P[3] %.4g)",
               config.name.c_str(), c.name.c_str(), c.link.c_str(), c.width, c.height,
               imageEncoding(c.format), c.horizontal_fov, c.publishRate(),
               cam.image.getTopic().c_str(), c.opticalFrame().c_str(), cam.sensor->info().P[3]);
    }
    const double rate = config.publishRate();
    schedule_.period = rate > 0.0 ? 1.0 / rate : 0.0;
    stat_ = setup.add_stat(cameras_.front().image.getTopic(), rate);
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    if (!schedule_.due(t)) return;
    unsigned want = 0;
    for (std::size_t i = 0; i < cameras_.size(); ++i) {
      if (cameras_[i].image.getNumSubscribers() > 0) want |= 1u << i;
    }
    SensorStat& stat = host.stat(stat_);
    if (want) {
      host.requestFrame({this, host.linkPose(robot_, link_), want});
      ++stat.count;
      ++stat.renders;
    } else {
      ++stat.skipped;
    }
    for (Camera& cam : cameras_) {
      if (cam.info.getNumSubscribers() == 0) continue;
      toCameraInfo(cam.sensor->info(), stamp, &info_msg_);
      cam.info.publish(info_msg_);
    }
  }

  void renderFrame(const Scene& scene, const FrameRequest& request,
                   const ros::Time& stamp) override {
    for (std::size_t i = 0; i < cameras_.size(); ++i) {
      if (!(request.outputs & (1u << i))) continue;
      Camera& cam = cameras_[i];
      cam.sensor->render(scene, request.X_WL);
      toImage(*cam.sensor, stamp, &cam.image_msg);
      cam.image.publish(cam.image_msg);
    }
  }

  void restart(double t) override { schedule_.restart(t); }

 private:
  struct Camera {
    std::unique_ptr<CameraSensor> sensor;
    ros::Publisher image, info;
    BorrowedImage image_msg;  // the sensor's buffer, serialised by publish() without a copy
  };

  std::size_t robot_;
  std::string link_;
  std::vector<Camera> cameras_;
  Schedule schedule_;
  sensor_msgs::CameraInfo info_msg_;
  std::size_t stat_ = 0;
};

}  // namespace

std::unique_ptr<SensorPublisher> makeMultiCameraPublisher(const SensorSetup& setup) {
  setup.check_link(setup.spec->link);
  // Parse first: a bad sensor is reported even when there is no renderer.
  MultiCameraConfig config = parseMultiCameraConfig(*setup.spec, setup.robot_name, setup.warn);
  if (!config.has_plugin) {
    setup.warn("robot '" + setup.robot_name + "': multicamera '" + setup.spec->name +
               "' has no gazebo_ros plugin: nothing to publish, left out");
    return nullptr;
  }
  if (config.cameras.size() > kMaxCameras) {
    throw CameraError("robot '" + setup.robot_name + "': multicamera sensor '" +
                      setup.spec->name + "' has " + std::to_string(config.cameras.size()) +
                      " cameras; at most " + std::to_string(kMaxCameras) + " are simulated");
  }
  Renderer* renderer = setup.renderer();
  if (!renderer) return nullptr;
  return std::make_unique<MultiCameraPublisher>(setup, std::move(config), *renderer);
}

}  // namespace tianracer_sim
