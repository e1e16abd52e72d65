// Robots' contacts (sim/contact_tracker.h) on /<robot namespace>/contacts (tianracer_sim/Contact):
// the tracker decides which are due, this publishes them where someone subscribes, and says
// whether anyone does (the node tracks contacts only then: Simulator::setContactTracking).
#ifndef TIANRACER_SIM_ROS_CONTACT_PUBLISHER_H
#define TIANRACER_SIM_ROS_CONTACT_PUBLISHER_H

#include <memory>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

class ContactPublisher {
 public:
  explicit ContactPublisher(const Simulator& sim) : sim_(sim), tracker_(sim.contacts()) {}

  void addRobot(ros::NodeHandle& nh, RobotId id, const std::string& name, const std::string& ns);
  /// Stops publishing for a robot that was deleted (its topic shuts down).
  void removeRobot(RobotId id);
  /// After the tracker's update: publishes its due contacts.
  void publish(double t);
  /// Whether any robot's contacts topic has a subscriber (kept by the publishers' connect and
  /// disconnect callbacks, which run on the node's queue between steps: no cost per step).
  bool subscribed() const {
    for (const Robot& r : robots_) {
      if (*r.subscribers > 0) return true;
    }
    return false;
  }

 private:
  struct Robot {
    RobotId id;
    std::string name;
    ros::Publisher pub;
    std::shared_ptr<int> subscribers;  // shared with the publisher's callbacks
  };

  const Simulator& sim_;
  const ContactTracker& tracker_;
  std::vector<Robot> robots_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTACT_PUBLISHER_H
