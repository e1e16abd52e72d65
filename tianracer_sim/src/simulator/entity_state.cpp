#include "tianracer_sim/simulator/entity_state.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace tianracer_sim {

ScopedName splitScopedName(const std::string& name) {
  const std::size_t sep = name.find("::");
  if (sep == std::string::npos) return {name, ""};
  return {name.substr(0, sep), name.substr(sep + 2)};
}

bool isWorldFrame(const std::string& name) {
  return name.empty() || name == "world" || name == "map";
}

EntityState relativeTo(const EntityState& entity, const EntityState& frame) {
  EntityState out;
  out.X_WE = frame.X_WE.inverse() * entity.X_WE;
  const Eigen::Matrix3d R_FW = frame.X_WE.linear().transpose();
  out.V_WE.linear = R_FW * (entity.V_WE.linear - frame.V_WE.linear);
  out.V_WE.angular = R_FW * (entity.V_WE.angular - frame.V_WE.angular);
  return out;
}

EntityState fromFrame(const EntityState& in_frame, const EntityState& frame) {
  EntityState out;
  out.X_WE = frame.X_WE * in_frame.X_WE;
  const Eigen::Matrix3d& R_WF = frame.X_WE.linear();
  out.V_WE.linear = R_WF * in_frame.V_WE.linear;
  out.V_WE.angular = R_WF * in_frame.V_WE.angular;
  return out;
}

Twist shiftTwist(const Twist& V_WL, const Eigen::Vector3d& p_WL, const Eigen::Vector3d& p_WB) {
  Twist out;
  out.angular = V_WL.angular;
  out.linear = V_WL.linear + V_WL.angular.cross(p_WB - p_WL);
  return out;
}

bool WrenchSchedule::add(ScheduledWrench w, double now, double duration, double dt) {
  if (duration == 0.0) return false;
  w.start = std::max(w.start, now);
  if (duration < 0.0) {
    w.end = std::numeric_limits<double>::infinity();
  } else {
    // At least one step: the wrench acts in every step whose start time lies in [start, end).
    w.end = w.start + std::max(duration, dt);
  }
  wrenches_.push_back(std::move(w));
  return true;
}

int WrenchSchedule::clear(const std::string& body) {
  const auto before = wrenches_.size();
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [&](const ScheduledWrench& w) {
                                   return body.empty() || w.body == body;
                                 }),
                  wrenches_.end());
  return static_cast<int>(before - wrenches_.size());
}

const std::vector<WrenchSchedule::Total>& WrenchSchedule::totals(double t) {
  // Half a nanosecond of slack: t is steps * dt, start and end are sums of such times.
  constexpr double kEps = 5e-10;
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(),
                                 [&](const ScheduledWrench& w) { return t + kEps >= w.end; }),
                  wrenches_.end());
  std::map<std::string, Total> sum;
  for (const std::string& b : active_) sum[b] = {b, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (const ScheduledWrench& w : wrenches_) {
    if (t + kEps < w.start) continue;
    auto it = sum.find(w.body);
    if (it == sum.end()) {
      it = sum.emplace(w.body, Total{w.body, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()})
               .first;
    }
    it->second.force_W += w.force_W;
    it->second.torque_W += w.torque_W;
  }
  totals_.clear();
  active_.clear();
  for (auto& [body, total] : sum) {
    totals_.push_back(total);
    if (!total.force_W.isZero(0.0) || !total.torque_W.isZero(0.0)) active_.push_back(body);
  }
  return totals_;
}

}  // namespace tianracer_sim
