#include "tianracer_sim/sim/contact_tracker.h"

#include <algorithm>

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
  // Then the actors' collisions, static shapes the Simulator moves (in this order).
  for (const ActorDescription& a : world.actors) {
    for (const LinkDescription& link : a.model.links) {
      for (size_t k = 0; k < link.collisions.size(); ++k) out.emplace_back(a.model.name, link.name);
    }
  }
  return out;
}

void ContactTracker::addRobot(RobotId id) {
  Robot r;
  r.id = id;
  robots_.push_back(std::move(r));
}

void ContactTracker::setStaticOwner(int index, const std::string& model, const std::string& link) {
  if (index < 0) return;
  if (index >= static_cast<int>(static_owners_.size())) static_owners_.resize(index + 1);
  static_owners_[index] = {model, link};
}

void ContactTracker::removeRobot(RobotId id) {
  robots_.erase(std::remove_if(robots_.begin(), robots_.end(),
                               [id](const Robot& r) { return r.id == id; }),
                robots_.end());
}

void ContactTracker::update(PhysicsWorld& world, double t) {
  due_.clear();
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
        it->second.second = -1.0;  // a new contact: reported now
      }
      it->second.first = t;
      if (it->second.second < 0.0 || t - it->second.second >= kReportPeriod - 1e-9) {
        it->second.second = t;
        due_.push_back({r.id, c});
      }
    }
  }
}

void ContactTracker::otherOf(const PhysicsWorld& world, const RobotContact& c, std::string* model,
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

std::uint64_t ContactTracker::count(RobotId id) const {
  for (const Robot& r : robots_) {
    if (r.id == id) return r.count;
  }
  return 0;
}

void ContactTracker::reset() {
  for (Robot& r : robots_) r.active.clear();
  due_.clear();
}

}  // namespace tianracer_sim
