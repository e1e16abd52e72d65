// Advertising a class's service callbacks, the servers kept by the class for its lifetime
// (GazeboInterface, ControllerManagerBridge).
#ifndef TIANRACER_SIM_ROS_SERVICE_ADVERTISER_H
#define TIANRACER_SIM_ROS_SERVICE_ADVERTISER_H

#include <string>
#include <utility>
#include <vector>

#include <ros/ros.h>

namespace tianracer_sim {

/// serve("name", &Owner::callback): advertises the service `name` on nh, served by
/// owner->callback, and adds its server to `servers`.
template <class Owner>
class ServiceAdvertiser {
 public:
  ServiceAdvertiser(ros::NodeHandle nh, Owner* owner, std::vector<ros::ServiceServer>* servers)
      : nh_(std::move(nh)), owner_(owner), servers_(servers) {}

  template <class Request, class Response>
  void operator()(const std::string& name, bool (Owner::*callback)(Request&, Response&)) {
    servers_->push_back(nh_.advertiseService(name, callback, owner_));
  }

 private:
  ros::NodeHandle nh_;
  Owner* owner_;
  std::vector<ros::ServiceServer>* servers_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_SERVICE_ADVERTISER_H
