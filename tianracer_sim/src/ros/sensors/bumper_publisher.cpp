// libgazebo_ros_bumper on a contact sensor: the link's contacts as gazebo_msgs/ContactsState
// (see sensors/bumper/bumper.h), published at the sensor's rate, empty when nothing touches.
#include <gazebo_msgs/ContactsState.h>

#include "factories.h"
#include "tianracer_sim/ros/bumper_msgs.h"

namespace tianracer_sim {
namespace {

class BumperPublisher : public SensorListener {
 public:
  BumperPublisher(SimBumper& sensor, const PublisherSetup& setup) {
    const BumperConfig& config = sensor.config();
    const std::string topic = config.topic();
    setup.claim_topic(topic, setup.owner() + " contact sensor '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<gazebo_msgs::ContactsState>(topic, 10);
    sensor.stat().name = topic;
    ROS_INFO("contact sensor '%s': link %s, frame %s, %g Hz on %s", config.name.c_str(),
             config.link.c_str(), sensor.frame().c_str(), config.update_rate, topic.c_str());
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }

  void onOutputs(const SimSensor& s, SensorOutputs, double t) override {
    const auto& sensor = static_cast<const SimBumper&>(s);
    toContactsState(sensor.states(), ros::Time(t), sensor.frame(), &msg_);
    pub_.publish(msg_);
  }

 private:
  ros::Publisher pub_;
  gazebo_msgs::ContactsState msg_;
};

}  // namespace

std::unique_ptr<SensorListener> makeBumperPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return std::make_unique<BumperPublisher>(static_cast<SimBumper&>(sensor), setup);
}

}  // namespace tianracer_sim
