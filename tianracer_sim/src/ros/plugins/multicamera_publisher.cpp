// multicamera sensors (gazebo_ros_multicamera, e.g. a stereo pair): every camera publishes as a
// camera sensor does, all on the SimMultiCamera's one schedule (one render per camera per
// period, only for cameras whose image has a subscriber). Images are published from the frame
// worker, camera_infos at the step.
#include <set>

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "factories.h"
#include "tianracer_sim/ros/borrowed_msgs.h"
#include "tianracer_sim/ros/camera_msgs.h"

namespace tianracer_sim {
namespace {

class MultiCameraPublisher : public SensorListener {
 public:
  MultiCameraPublisher(SimMultiCamera& sensor, const PublisherSetup& setup) {
    const MultiCameraConfig& config = sensor.config();
    const std::string owner = setup.owner() + " multicamera '" + sensor.name() + "'";
    std::set<std::string> frames_sent;
    cameras_.resize(sensor.size());
    for (std::size_t i = 0; i < sensor.size(); ++i) {
      const CameraConfig& c = config.cameras[i];
      ros::NodeHandle nh(setup.root, resolveTopic(c.robot_namespace, c.camera_name));
      setup.claim_topic(nh.getNamespace(), owner + " camera '" + c.name + "'");
      // One optical frame per frame name: cameras sharing a frameName are stamped with the
      // first one's frame, as Gazebo stamps them; P[3] carries the right camera's offset.
      if (!c.frame_is_optical && frames_sent.insert(c.opticalFrame()).second)
        sendOpticalFrame(setup, sensor.link().link, c);
      Camera& cam = cameras_[i];
      cam.image = nh.advertise<sensor_msgs::Image>(c.image_topic, 2);
      cam.info = nh.advertise<sensor_msgs::CameraInfo>(c.camera_info_topic, 2);
      ROS_INFO("multicamera '%s' camera '%s' on link %s: %dx%d %s, hfov %.4g, %g Hz on %s "
               "(frame %s, P[3] %.4g)",
               config.name.c_str(), c.name.c_str(), c.link.c_str(), c.width, c.height,
               imageEncoding(c.format), c.horizontal_fov, c.publishRate(),
               cam.image.getTopic().c_str(), c.opticalFrame().c_str(), sensor.camera(i).info().P[3]);
    }
    sensor.stat().name = cameras_.front().image.getTopic();
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs) override {
    SensorOutputs want = 0;
    for (std::size_t i = 0; i < cameras_.size(); ++i) {
      if (cameras_[i].image.getNumSubscribers() > 0) want |= SimMultiCamera::image(i);
      if (cameras_[i].info.getNumSubscribers() > 0) want |= SimMultiCamera::info(i);
    }
    return want;
  }

  void onOutputs(const SimSensor& s, SensorOutputs outputs, double t) override {
    const auto& sensor = static_cast<const SimMultiCamera&>(s);
    const ros::Time stamp(t);
    for (std::size_t i = 0; i < cameras_.size(); ++i) {
      Camera& cam = cameras_[i];
      if (outputs & SimMultiCamera::image(i)) {  // on the frame worker
        toImage(sensor.camera(i), stamp, &cam.image_msg);
        cam.image.publish(cam.image_msg);
      }
      if (outputs & SimMultiCamera::info(i)) {
        toCameraInfo(sensor.camera(i).info(), stamp, &info_msg_);
        cam.info.publish(info_msg_);
      }
    }
  }

 private:
  struct Camera {
    ros::Publisher image, info;
    BorrowedImage image_msg;  // the sensor's buffer, serialised by publish() without a copy
  };

  std::vector<Camera> cameras_;
  sensor_msgs::CameraInfo info_msg_;
};

}  // namespace

std::unique_ptr<SensorListener> makeMultiCameraPublisher(SimSensor& sensor,
                                                         const PublisherSetup& setup) {
  return std::make_unique<MultiCameraPublisher>(static_cast<SimMultiCamera&>(sensor), setup);
}

TIANRACER_SENSOR_PUBLISHER(multiCameraKind, makeMultiCameraPublisher);

}  // namespace tianracer_sim
