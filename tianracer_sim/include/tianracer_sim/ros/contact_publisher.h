// Robots' contacts (physics/contacts.h) on /<robot namespace>/contacts (tianracer_sim/Contact),
// with the count of contacts begun per robot for /diagnostics.
#ifndef TIANRACER_SIM_ROS_CONTACT_PUBLISHER_H
#define TIANRACER_SIM_ROS_CONTACT_PUBLISHER_H

#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <ros/ros.h>

#include "tianracer_sim/physics/contacts.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// (model, link) of every static shape, in the order addWorldToPhysics adds them: the
/// collisions of static models and of models fixed to "world", model by model.
std::vector<std::pair<std::string, std::string>> staticShapeOwners(const WorldDescription& world);

class ContactPublisher {
 public:
  /// Contacts that begin less than this (s) after the same pair's last one are the same contact.
  static constexpr double kSameContactGap = 0.1;
  /// While a contact lasts it is published at most this often (s of sim time).
  static constexpr double kPublishPeriod = 0.01;

  explicit ContactPublisher(std::vector<std::pair<std::string, std::string>> static_owners)
      : static_owners_(std::move(static_owners)) {}

  void addRobot(ros::NodeHandle& nh, RobotId id, const std::string& name, const std::string& ns);
  /// Names the owner of a static shape added after start-up (spawn_sdf_model).
  void setStaticOwner(int index, const std::string& model, const std::string& link);
  /// Stops publishing for a robot that was deleted (its topic shuts down).
  void removeRobot(RobotId id);
  /// After each step: queries every robot's contacts, publishes the due ones.
  void update(PhysicsWorld& world, double t);
  /// The other object of a contact: model name and link ("" for a static shape's or the
  /// ground's own).
  void otherOf(PhysicsWorld& world, const RobotContact& c, std::string* model, std::string* link) const;
  /// Contacts begun since the start (a pair touching again after kSameContactGap counts again).
  std::uint64_t count(RobotId id) const;
  /// Forget contacts in progress (time jumped back on a reset).
  void reset();

 private:
  struct Robot {
    RobotId id;
    std::string name;
    ros::Publisher pub;
    std::uint64_t count = 0;
    // (body, other kind, other index, other body) -> (last seen, last published)
    std::map<std::tuple<int, int, int, int>, std::pair<double, double>> active;
  };
  void publish(PhysicsWorld& world, Robot& r, const RobotContact& c, double t);

  std::vector<std::pair<std::string, std::string>> static_owners_;
  std::vector<Robot> robots_;
  std::vector<RobotContact> scratch_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTACT_PUBLISHER_H
