// libgazebo_ros_p3d: a link's ground truth as nav_msgs/Odometry (see sensors/p3d.h).
#include <nav_msgs/Odometry.h>

#include <tianracer_control/frames.h>

#include "factories.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {
namespace {

class P3dPublisher : public SensorPublisher {
 public:
  P3dPublisher(const SensorSetup& setup, P3dConfig config) : robot_(setup.robot) {
    config.seed = setup.seed + 401 + static_cast<std::uint64_t>(setup.index);
    setup.check_link(config.link);
    if (!config.reference_link.empty()) setup.check_link(config.reference_link);
    // Frames as the sim's others: tf_prefix on links, world as it is.
    frame_ = config.reference_link.empty()
                 ? config.frame_name
                 : tianracer_control::resolveFrame(setup.tf_prefix, config.reference_link);
    child_ = tianracer_control::resolveFrame(setup.tf_prefix, config.link);
    sensor_ = std::make_unique<P3dSensor>(config);
    const std::string topic = config.topic();
    setup.claim_topic(topic, "robot '" + setup.robot_name + "' p3d '" + config.name + "'");
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<nav_msgs::Odometry>(topic, 10);
    schedule_.period = config.update_rate > 0.0 ? 1.0 / config.update_rate : 0.0;
    stat_ = setup.add_stat(topic, config.update_rate);
    ROS_INFO("p3d '%s': link %s in %s, %g Hz on %s", config.name.c_str(), config.link.c_str(),
             frame_.c_str(), config.update_rate, topic.c_str());
  }

  void step(double t, const ros::Time& stamp, SensorHost& host) override {
    // Velocities of links off the root body are pose differences: keep the history each step.
    const P3dConfig& c = sensor_->config();
    track(t, host, c.link, &body_);
    if (!c.reference_link.empty()) track(t, host, c.reference_link, &reference_);
    if (!schedule_.due(t)) return;
    SensorStat& stat = host.stat(stat_);
    if (pub_.getNumSubscribers() == 0) {
      ++stat.skipped;
      return;
    }
    const P3dReading& r = sensor_->measure(
        body_.state(), c.reference_link.empty() ? nullptr : &reference_.state());
    toOdometry(r, stamp, frame_, child_, &msg_);
    pub_.publish(msg_);
    ++stat.count;
    ++stat.renders;
  }

  void restart(double t) override {
    schedule_.restart(t);
    body_.reset();
    reference_.reset();
  }

 private:
  void track(double t, SensorHost& host, const std::string& link, LinkMotion* motion) {
    LinkState exact;
    if (host.linkState(robot_, link, &exact)) {
      motion->set(t, exact);
    } else {
      motion->record(t, host.linkPose(robot_, link));
    }
  }

  std::size_t robot_;
  std::unique_ptr<P3dSensor> sensor_;
  std::string frame_, child_;
  LinkMotion body_, reference_;
  ros::Publisher pub_;
  Schedule schedule_;
  nav_msgs::Odometry msg_;
  std::size_t stat_ = 0;
};

}  // namespace

std::unique_ptr<SensorPublisher> makeP3dPublisher(const SensorSetup& setup) {
  return std::make_unique<P3dPublisher>(setup,
                                        parseP3dConfig(*setup.spec, setup.robot_name, setup.warn));
}

}  // namespace tianracer_sim
