// Robots' contacts over time (physics/contacts.h gives them per step): which are new, which are
// due to be reported, how many began per robot, and what the other side is called. ROS-free:
// the node publishes the due ones on /<robot namespace>/contacts.
#ifndef TIANRACER_SIM_SIM_CONTACT_TRACKER_H
#define TIANRACER_SIM_SIM_CONTACT_TRACKER_H

#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tianracer_sim/physics/contacts.h"
#include "tianracer_sim/physics/world.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {

/// (model, link) of every static shape, in the order addWorldToPhysics adds them: the
/// collisions of static models and of models fixed to "world", model by model.
std::vector<std::pair<std::string, std::string>> staticShapeOwners(const WorldDescription& world);

class ContactTracker {
 public:
  /// Contacts that begin less than this (s) after the same pair's last one are the same contact.
  static constexpr double kSameContactGap = 0.1;
  /// While a contact lasts it is reported at most this often (s of sim time).
  static constexpr double kReportPeriod = 0.01;

  /// A contact to report at this step.
  struct Due {
    RobotId robot = -1;
    RobotContact contact;
  };

  explicit ContactTracker(std::vector<std::pair<std::string, std::string>> static_owners = {})
      : static_owners_(std::move(static_owners)) {}

  void addRobot(RobotId id);
  /// Names the owner of a static shape added after start-up (spawn_sdf_model).
  void setStaticOwner(int index, const std::string& model, const std::string& link);
  void removeRobot(RobotId id);
  /// After each step: queries every robot's contacts, counts the new ones and lists the ones
  /// due to be reported in due() (new, or kReportPeriod after the pair's last report).
  void update(PhysicsWorld& world, double t);
  const std::vector<Due>& due() const { return due_; }
  /// The other object of a contact: model name and link ("" for a static shape's or the
  /// ground's own).
  void otherOf(const PhysicsWorld& world, const RobotContact& c, std::string* model,
               std::string* link) const;
  /// (model, link) of each static shape, by its index.
  const std::vector<std::pair<std::string, std::string>>& staticOwners() const {
    return static_owners_;
  }
  /// Contacts begun since the start while contacts were tracked (a pair touching again after
  /// kSameContactGap counts again).
  std::uint64_t count(RobotId id) const;
  /// Forget contacts in progress and the due ones (time jumped back on a reset, or tracking
  /// stopped: a contact still there when it resumes is a new one).
  void reset();

 private:
  struct Robot {
    RobotId id;
    std::uint64_t count = 0;
    // (body, other kind, other index, other body) -> (last seen, last reported)
    std::map<std::tuple<int, int, int, int>, std::pair<double, double>> active;
  };

  std::vector<std::pair<std::string, std::string>> static_owners_;
  std::vector<Robot> robots_;
  std::vector<RobotContact> scratch_;
  std::vector<Due> due_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_CONTACT_TRACKER_H
