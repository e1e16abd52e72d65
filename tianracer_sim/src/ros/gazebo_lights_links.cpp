// gazebo_ros's light and link property services (gazebo_ros/src/gazebo_ros_api_plugin.cpp,
// noetic-devel): get/set_light_properties, delete_light, get/set_link_properties. Thin, as
// gazebo_properties.cpp: the Simulator checks and changes the state.
#include <tianracer_control/ros/msg_conversion.h>

#include "gazebo_answer.h"
#include "tianracer_sim/ros/gazebo_interface.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {

namespace {

std_msgs::ColorRGBA toColor(const Eigen::Vector4f& c) {
  std_msgs::ColorRGBA m;
  m.r = c[0];
  m.g = c[1];
  m.b = c[2];
  m.a = c[3];
  return m;
}

Eigen::Vector4f fromColor(const std_msgs::ColorRGBA& m) { return {m.r, m.g, m.b, m.a}; }

/// What we answer in ODE's fields: the solver's settings in Bullet's terms (docs).
}  // namespace

// --- lights -----------------------------------------------------------------------------------

bool GazeboInterface::getLightProperties(gazebo_msgs::GetLightProperties::Request& req,
                                         gazebo_msgs::GetLightProperties::Response& res) {
  res.success = false;
  for (const DirectionalLight& l : simulator_.properties().lights()) {
    if (l.name != req.light_name) continue;
    res.diffuse = toColor(l.given_diffuse);
    res.attenuation_constant = l.attenuation.constant;
    res.attenuation_linear = l.attenuation.linear;
    res.attenuation_quadratic = l.attenuation.quadratic;
    return succeeded(res, "GetLightProperties: got properties");
  }
  res.status_message = "getLightProperties: Requested light " + req.light_name + " not found!";
  return true;
}

bool GazeboInterface::setLightProperties(gazebo_msgs::SetLightProperties::Request& req,
                                         gazebo_msgs::SetLightProperties::Response& res) {
  LightChange c;
  c.diffuse = fromColor(req.diffuse);
  c.specular = fromColor(req.specular);
  c.attenuation = {req.attenuation_constant, req.attenuation_linear, req.attenuation_quadratic};
  c.direction = Eigen::Vector3d(req.direction.x, req.direction.y, req.direction.z);
  return answer(res, {"set_light_properties: "}, [&] {
    simulator_.properties().setLight(req.light_name, c);
    return "SetLightProperties: properties set";
  });
}

bool GazeboInterface::deleteLight(gazebo_msgs::DeleteLight::Request& req,
                                  gazebo_msgs::DeleteLight::Response& res) {
  res.success = false;
  try {
    simulator_.properties().deleteLight(req.light_name);
    res.success = true;
    res.status_message = "DeleteLight: " + req.light_name + " successfully deleted";
  } catch (const InputError& e) {
    res.status_message = "DeleteLight: Requested light " + req.light_name + " not found!";
  }
  return true;
}

// --- links ------------------------------------------------------------------------------------

bool GazeboInterface::getLinkProperties(gazebo_msgs::GetLinkProperties::Request& req,
                                        gazebo_msgs::GetLinkProperties::Response& res) {
  return answer(res, {"get_link_properties: ", "", false}, [&] {
    const LinkProperties l = simulator_.properties().linkProperties(req.link_name);
    tianracer_control::toXyzMsg(l.com, &res.com.position);
    res.com.orientation.w = 1.0;  // as gazebo_ros: no rotated inertia
    res.gravity_mode = l.gravity_mode;
    res.mass = l.mass;
    res.ixx = l.inertia(0, 0);
    res.ixy = l.inertia(0, 1);
    res.ixz = l.inertia(0, 2);
    res.iyy = l.inertia(1, 1);
    res.iyz = l.inertia(1, 2);
    res.izz = l.inertia(2, 2);
    return "GetLinkProperties: got properties";
  });
}

bool GazeboInterface::setLinkProperties(gazebo_msgs::SetLinkProperties::Request& req,
                                        gazebo_msgs::SetLinkProperties::Response& res) {
  res.success = false;
  try {
    simulator_.properties().linkProperties(req.link_name);  // names an unknown link first
    res.status_message = "set_link_properties: link '" + req.link_name +
                         "': mass, inertia, centre of mass and gravity mode are fixed once the "
                         "model is built here (a Bullet multibody's); nothing changed";
  } catch (const InputError& e) {
    res.status_message = std::string("set_link_properties: ") + e.what();
  }
  ROS_WARN_STREAM(res.status_message);
  return true;
}

}  // namespace tianracer_sim
