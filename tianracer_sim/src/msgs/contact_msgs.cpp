#include "tianracer_sim/ros/contact_msgs.h"

#include <tianracer_control/ros/msg_conversion.h>

namespace tianracer_sim {

void toContact(const RobotContact& contact, const ros::Time& stamp, const std::string& robot,
               const std::string& link, tianracer_sim::Contact* msg) {
  msg->stamp = stamp;
  msg->robot = robot;
  msg->link = link;
  tianracer_control::toXyzMsg(contact.position_W, &msg->position);
  tianracer_control::toXyzMsg(contact.normal_W, &msg->normal);
  msg->depth = contact.depth;
  msg->impulse = contact.impulse;
}

}  // namespace tianracer_sim
