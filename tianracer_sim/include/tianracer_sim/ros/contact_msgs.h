// A robot's contact (physics/contacts.h) -> tianracer_sim/Contact (msg/Contact.msg).
#ifndef TIANRACER_SIM_ROS_CONTACT_MSGS_H
#define TIANRACER_SIM_ROS_CONTACT_MSGS_H

#include <string>

#include <ros/time.h>

#include "tianracer_sim/Contact.h"
#include "tianracer_sim/physics/contacts.h"

namespace tianracer_sim {

/// Stamp, robot, link and the contact's point, normal (world frame), depth and impulse.
/// other_model and other_link are the caller's (they take the world: ContactTracker::otherOf).
void toContact(const RobotContact& contact, const ros::Time& stamp, const std::string& robot,
               const std::string& link, tianracer_sim::Contact* msg);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_CONTACT_MSGS_H
