#include "tianracer_sim/ros/bumper_msgs.h"

namespace tianracer_sim {
namespace {

geometry_msgs::Vector3 vec(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

}  // namespace

void toContactsState(const std::vector<BumperState>& states, const ros::Time& stamp,
                     const std::string& frame_id, gazebo_msgs::ContactsState* msg) {
  msg->header.stamp = stamp;
  msg->header.frame_id = frame_id;
  msg->states.resize(states.size());
  for (size_t i = 0; i < states.size(); ++i) {
    const BumperState& s = states[i];
    gazebo_msgs::ContactState& m = msg->states[i];
    m.info = s.collision1 + " touches " + s.collision2;
    m.collision1_name = s.collision1;
    m.collision2_name = s.collision2;
    m.wrenches.resize(s.forces.size());
    m.contact_positions.resize(s.positions.size());
    m.contact_normals.resize(s.normals.size());
    for (size_t k = 0; k < s.forces.size(); ++k) {
      m.wrenches[k].force = vec(s.forces[k]);
      m.wrenches[k].torque = geometry_msgs::Vector3();
      m.contact_positions[k] = vec(s.positions[k]);
      m.contact_normals[k] = vec(s.normals[k]);
    }
    m.total_wrench.force = vec(s.total_force);
    m.total_wrench.torque = geometry_msgs::Vector3();
    m.depths = s.depths;
  }
}

}  // namespace tianracer_sim
