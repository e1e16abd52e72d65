// libgazebo_ros_bumper on a contact sensor: the link's contacts as gazebo_msgs/ContactsState
// (see sensors/bumper.h), published at the sensor's rate, empty when nothing touches.
#include <gazebo_msgs/ContactsState.h>

#include <tianracer_control/frames.h>

#include "factories.h"
#include "tianracer_sim/lidar/ray_sensor.h"  // SensorError
#include "tianracer_sim/ros/bumper_msgs.h"

namespace tianracer_sim {
namespace {

class BumperPublisher : public SensorPublisher {
 public:
  BumperPublisher(const SensorSetup& setup, BumperConfig config)
      : robot_(setup.robot), config_(std::move(config)), dt_(setup.dt) {
    setup.check_link(config_.link);
    const bool world = config_.frame_name == "world" || config_.frame_name == "map";
    if (!world) {
      try {
        setup.check_link(config_.frame_name);
      } catch (const std::exception&) {
        throw SensorError("contact sensor '" + config_.name + "' of model '" + setup.robot_name +
                          "': <frameName> '" + config_.frame_name +
                          "' is neither world nor a link of the model");
      }
      frame_link_ = config_.frame_name;
    }
    frame_id_ = world ? config_.frame_name
                      : tianracer_control::resolveFrame(setup.tf_prefix, config_.frame_name);
    const std::string topic = config_.topic();
    setup.claim_topic(topic, "robot '" + setup.robot_name + "' contact sensor '" + config_.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<gazebo_msgs::ContactsState>(topic, 10);
    schedule_.period = config_.update_rate > 0.0 ? 1.0 / config_.update_rate : 0.0;
    stat_ = setup.add_stat(topic, config_.update_rate);
    ROS_INFO("contact sensor '%s': link %s, frame %s, %g Hz on %s", config_.name.c_str(),
             config_.link.c_str(), frame_id_.c_str(), config_.update_rate, topic.c_str());
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    if (!schedule_.due(t)) return;
    SensorStat& stat = host.stat(stat_);
    if (pub_.getNumSubscribers() == 0) {
      ++stat.skipped;
      return;
    }
    host.linkContacts(robot_, config_.link, &contacts_);
    const Eigen::Isometry3d X_WF =
        frame_link_.empty() ? Eigen::Isometry3d::Identity() : host.linkPose(robot_, frame_link_);
    bumperStates(contacts_, X_WF, dt_, &states_);
    toContactsState(states_, stamp, frame_id_, &msg_);
    pub_.publish(msg_);
    ++stat.count;
    ++stat.renders;
  }

  void restart(double t) override { schedule_.restart(t); }

 private:
  std::size_t robot_;
  BumperConfig config_;
  double dt_;
  std::string frame_link_, frame_id_;
  ros::Publisher pub_;
  Schedule schedule_;
  std::vector<BumperContact> contacts_;
  std::vector<BumperState> states_;
  gazebo_msgs::ContactsState msg_;
  std::size_t stat_ = 0;
};

}  // namespace

std::unique_ptr<SensorPublisher> makeBumperPublisher(const SensorSetup& setup) {
  BumperConfig config = parseBumperConfig(*setup.spec, setup.robot_name, setup.warn);
  if (config.topic_name.empty()) {
    if (setup.warn) {
      setup.warn("contact sensor '" + config.name + "' of model '" + setup.robot_name +
                 "' has no libgazebo_ros_bumper plugin: nothing published (as in Gazebo)");
    }
    return nullptr;
  }
  return std::make_unique<BumperPublisher>(setup, std::move(config));
}

}  // namespace tianracer_sim
