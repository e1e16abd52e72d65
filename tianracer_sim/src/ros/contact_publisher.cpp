#include "tianracer_sim/ros/contact_publisher.h"

#include <algorithm>

#include "tianracer_sim/Contact.h"

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

void ContactPublisher::publish(const PhysicsWorld& world, double t) {
  for (const ContactTracker::Due& d : tracker_.due()) {
    const auto r = std::find_if(robots_.begin(), robots_.end(),
                                [&](const Robot& x) { return x.id == d.robot; });
    if (r == robots_.end() || *r->subscribers == 0) continue;
    const RobotContact& c = d.contact;
    tianracer_sim::Contact msg;
    msg.stamp = ros::Time(t);
    msg.robot = r->name;
    msg.link = world.robot(r->id).tree().bodies.at(c.body).link;
    tracker_.otherOf(world, c, &msg.other_model, &msg.other_link);
    msg.position.x = c.position_W.x();
    msg.position.y = c.position_W.y();
    msg.position.z = c.position_W.z();
    msg.normal.x = c.normal_W.x();
    msg.normal.y = c.normal_W.y();
    msg.normal.z = c.normal_W.z();
    msg.depth = c.depth;
    msg.impulse = c.impulse;
    r->pub.publish(msg);
  }
}

}  // namespace tianracer_sim
