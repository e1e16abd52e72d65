#include "tianracer_sim/ros/contact_publisher.h"

#include <algorithm>

#include "tianracer_sim/ros/contact_msgs.h"

namespace tianracer_sim {

void ContactPublisher::addRobot(ros::NodeHandle& nh, RobotId id, const std::string& name,
                                const std::string& ns) {
  Robot r;
  r.id = id;
  r.name = name;
  r.subscribers = std::make_shared<int>(0);
  std::shared_ptr<int> count = r.subscribers;
  r.pub = nh.advertise<tianracer_sim::Contact>(
      ns + "/contacts", 100, [count](const ros::SingleSubscriberPublisher&) { ++*count; },
      [count](const ros::SingleSubscriberPublisher&) { --*count; });
  robots_.push_back(std::move(r));
}

void ContactPublisher::removeRobot(RobotId id) {
  robots_.erase(std::remove_if(robots_.begin(), robots_.end(),
                               [id](const Robot& r) { return r.id == id; }),
                robots_.end());
}

void ContactPublisher::publish(double t) {
  for (const ContactTracker::Due& d : tracker_.due()) {
    const auto r = std::find_if(robots_.begin(), robots_.end(),
                                [&](const Robot& x) { return x.id == d.robot; });
    if (r == robots_.end() || *r->subscribers == 0) continue;
    const RobotContact& c = d.contact;
    tianracer_sim::Contact msg;
    std::string link;
    sim_.contactNames(r->id, c, &link, &msg.other_model, &msg.other_link);
    toContact(c, ros::Time(t), r->name, link, &msg);
    r->pub.publish(msg);
  }
}

}  // namespace tianracer_sim
