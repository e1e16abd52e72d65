#include "tianracer_control/ros/controller_ros.h"

#include <map>
#include <sstream>

#include <ros/console.h>
#include <ros/time.h>

namespace tianracer_control {

namespace {
std::map<std::string, RosSideFactory>& rosSides() {
  static std::map<std::string, RosSideFactory> sides;  // made on first use: any static order
  return sides;
}
}  // namespace

bool registerRosSide(const std::string& type, RosSideFactory factory) {
  rosSides()[type] = factory;
  return true;
}

RosSideFactory findRosSide(const std::string& type) {
  const auto it = rosSides().find(type);
  return it == rosSides().end() ? nullptr : it->second;
}

void ThrottledWarning::warn(const std::string& text) {
  const double now = ros::WallTime::now().toSec();
  if (last_ >= 0.0 && now - last_ < 1.0) {
    ++held_back_;
    return;
  }
  std::ostringstream os;
  os << text;
  if (held_back_ > 0) os << "; " << held_back_ << " more ignored since the last warning";
  ROS_WARN_STREAM(os.str());
  last_ = now;
  held_back_ = 0;
}

}  // namespace tianracer_control
