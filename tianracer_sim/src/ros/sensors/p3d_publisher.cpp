// libgazebo_ros_p3d: a link's ground truth as nav_msgs/Odometry (see sensors/p3d/p3d.h).
#include <nav_msgs/Odometry.h>

#include "factories.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {
namespace {

class P3dPublisher : public SensorListener {
 public:
  P3dPublisher(SimP3d& sensor, const PublisherSetup& setup) {
    const P3dConfig& config = sensor.config();
    const std::string topic = config.topic();
    setup.claim_topic(topic, setup.owner() + " p3d '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<nav_msgs::Odometry>(topic, 10);
    sensor.stat().name = topic;
    ROS_INFO("p3d '%s': link %s in %s, %g Hz on %s", config.name.c_str(), config.link.c_str(),
             sensor.frame().c_str(), config.update_rate, topic.c_str());
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }

  void onOutputs(const SimSensor& s, SensorOutputs, double t) override {
    const auto& sensor = static_cast<const SimP3d&>(s);
    toOdometry(sensor.reading(), ros::Time(t), sensor.frame(), sensor.childFrame(), &msg_);
    pub_.publish(msg_);
  }

 private:
  ros::Publisher pub_;
  nav_msgs::Odometry msg_;
};

}  // namespace

std::unique_ptr<SensorListener> makeP3dPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<P3dPublisher>(static_cast<SimP3d&>(sensor), setup);
}

}  // namespace tianracer_sim
