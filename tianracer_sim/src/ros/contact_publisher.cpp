#include "tianracer_sim/ros/contact_publisher.h"

#include <algorithm>

#include "tianracer_sim/Contact.h"

namespace tianracer_sim {

std::vector<std::pair<std::string, std::string>> staticShapeOwners(const WorldDescription& world) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const ModelDescription& model : world.models) {
    bool fixed = false;
    for (const JointDescription& j : model.joints) {
      if (j.parent == "world" || j.child == "world") fixed = true;
    }
    if (!model.is_static && !fixed && !model.links.empty()) continue;  // a free body
    for (const LinkDescription& link : model.links) {
      for (size_t k = 0; k < link.collisions.size(); ++k) out.emplace_back(model.name, link.name);
    }
  }
  return out;
}

void ContactPublisher::addRobot(ros::NodeHandle& nh, RobotId id, const std::string& name,
                                const std::string& ns) {
  Robot r;
  r.id = id;
  r.name = name;
  r.pub = nh.advertise<tianracer_sim::Contact>(ns + "/contacts", 100);
  robots_.push_back(std::move(r));
}

void ContactPublisher::setStaticOwner(int index, const std::string& model,
                                      const std::string& link) {
  if (index < 0) return;
  if (index >= static_cast<int>(static_owners_.size())) static_owners_.resize(index + 1);
  static_owners_[index] = {model, link};
}

void ContactPublisher::removeRobot(RobotId id) {
  robots_.erase(std::remove_if(robots_.begin(), robots_.end(),
                               [id](const Robot& r) { return r.id == id; }),
                robots_.end());
}

void ContactPublisher::update(PhysicsWorld& world, double t) {
  for (Robot& r : robots_) {
    robotContacts(world, r.id, &scratch_);
    for (const RobotContact& c : scratch_) {
      const int kind = c.other_robot >= 0 ? 0 : c.other_free_body >= 0 ? 1 : c.other_static >= 0 ? 2 : 3;
      const int index = kind == 0 ? c.other_robot : kind == 1 ? c.other_free_body : c.other_static;
      auto key = std::make_tuple(c.body, kind, index, c.other_body);
      auto it = r.active.find(key);
      if (it == r.active.end() || t - it->second.first > kSameContactGap) {
        ++r.count;
        if (it == r.active.end()) it = r.active.emplace(key, std::make_pair(t, -1.0)).first;
        it->second.second = -1.0;  // a new contact: published now
      }
      it->second.first = t;
      if (it->second.second < 0.0 || t - it->second.second >= kPublishPeriod - 1e-9) {
        it->second.second = t;
        if (r.pub.getNumSubscribers() > 0) publish(world, r, c, t);
      }
    }
  }
}

void ContactPublisher::publish(PhysicsWorld& world, Robot& r, const RobotContact& c, double t) {
  tianracer_sim::Contact msg;
  msg.stamp = ros::Time(t);
  msg.robot = r.name;
  const PhysicsRobot& own = world.robot(r.id);
  msg.link = own.tree().bodies.at(c.body).link;
  otherOf(world, c, &msg.other_model, &msg.other_link);
  msg.position.x = c.position_W.x();
  msg.position.y = c.position_W.y();
  msg.position.z = c.position_W.z();
  msg.normal.x = c.normal_W.x();
  msg.normal.y = c.normal_W.y();
  msg.normal.z = c.normal_W.z();
  msg.depth = c.depth;
  msg.impulse = c.impulse;
  r.pub.publish(msg);
}

void ContactPublisher::otherOf(PhysicsWorld& world, const RobotContact& c, std::string* model,
                               std::string* link) const {
  link->clear();
  if (c.other_robot >= 0) {
    const PhysicsRobot& o = world.robot(c.other_robot);
    *model = o.name();
    *link = o.tree().bodies.at(c.other_body).link;
  } else if (c.other_free_body >= 0) {
    const PhysicsRobot& o = world.freeBody(c.other_free_body);
    *model = o.name();
    *link = o.tree().bodies.at(c.other_body).link;
  } else if (c.other_static >= 0 && c.other_static < static_cast<int>(static_owners_.size())) {
    *model = static_owners_[c.other_static].first;
    *link = static_owners_[c.other_static].second;
  } else if (c.other_static >= 0) {
    *model = "static shape " + std::to_string(c.other_static);
  } else {
    *model = "ground_plane";
  }
}

std::uint64_t ContactPublisher::count(RobotId id) const {
  for (const Robot& r : robots_) {
    if (r.id == id) return r.count;
  }
  return 0;
}

void ContactPublisher::reset() {
  for (Robot& r : robots_) r.active.clear();
}

}  // namespace tianracer_sim
