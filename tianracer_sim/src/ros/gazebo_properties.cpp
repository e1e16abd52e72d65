// gazebo_ros's property services (gazebo_ros/src/gazebo_ros_api_plugin.cpp, noetic-devel):
// joints, physics, lights, links, set_model_configuration, apply_joint_effort and
// clear_joint_forces, and the physics' dynamic_reconfigure parameters. Thin: the Simulator
// checks and changes the state (simulator/properties.h); a refusal (InputError) answers
// success false with its message, and nothing changes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>

#include <tianracer_control/ros/msg_conversion.h>

#include "gazebo_answer.h"
#include "tianracer_sim/ros/gazebo_interface.h"

namespace tianracer_sim {

namespace {

gazebo_msgs::ODEPhysics odeConfig(const PhysicsProperties& p) {
  gazebo_msgs::ODEPhysics o;
  o.auto_disable_bodies = p.auto_disable_bodies;
  o.sor_pgs_precon_iters = 0;
  o.sor_pgs_iters = static_cast<std::uint32_t>(p.solver_iterations);
  o.sor_pgs_w = p.solver.sor;
  o.sor_pgs_rms_error_tol = p.solver.residual_threshold;
  o.contact_surface_layer = 0.0;  // per surface (<min_depth>), none world-wide
  o.contact_max_correcting_vel = p.contact_max_correcting_vel;
  o.cfm = p.solver.global_cfm;
  o.erp = p.solver.erp;
  o.max_contacts = 4;  // Bullet's contact manifold keeps at most 4 points per pair of bodies
  return o;
}

/// The ODE fields of a request into `p`: iters and contact_max_correcting_vel are set; the
/// others must be what we answer. An all-zero ODEPhysics (a request that fills only time
/// step, rate and gravity) leaves them alone. "" or what is refused.
std::string applyOde(const gazebo_msgs::ODEPhysics& o, PhysicsProperties* p) {
  if (o == gazebo_msgs::ODEPhysics()) return "";
  const gazebo_msgs::ODEPhysics now = odeConfig(*p);
  auto differs = [](const char* field, double got, double have) {
    std::ostringstream os;
    os << "ode_config." << field << " " << got << " cannot be set here (it is " << have
       << "; Bullet's solver has no such setting to change)";
    return os.str();
  };
  if (o.sor_pgs_precon_iters != now.sor_pgs_precon_iters)
    return differs("sor_pgs_precon_iters", o.sor_pgs_precon_iters, now.sor_pgs_precon_iters);
  if (o.sor_pgs_w != now.sor_pgs_w) return differs("sor_pgs_w", o.sor_pgs_w, now.sor_pgs_w);
  if (o.sor_pgs_rms_error_tol != now.sor_pgs_rms_error_tol)
    return differs("sor_pgs_rms_error_tol", o.sor_pgs_rms_error_tol, now.sor_pgs_rms_error_tol);
  if (o.contact_surface_layer != now.contact_surface_layer)
    return differs("contact_surface_layer", o.contact_surface_layer, now.contact_surface_layer);
  if (o.cfm != now.cfm) return differs("cfm", o.cfm, now.cfm);
  if (o.erp != now.erp) return differs("erp", o.erp, now.erp);
  if (o.max_contacts != now.max_contacts) return differs("max_contacts", o.max_contacts, now.max_contacts);
  p->auto_disable_bodies = o.auto_disable_bodies;  // the Simulator refuses a change
  p->solver_iterations = static_cast<int>(o.sor_pgs_iters);
  p->contact_max_correcting_vel = o.contact_max_correcting_vel;
  return "";
}

/// gazebo_ros's physics reconfigure parameters (gazebo_ros cfg/Physics.cfg's names).
struct ReconfigureParam {
  const char* name;
  const char* type;  // "double", "int", "bool"
};
const ReconfigureParam kPhysicsParams[] = {
    {"time_step", "double"},           {"max_update_rate", "double"},
    {"gravity_x", "double"},           {"gravity_y", "double"},
    {"gravity_z", "double"},           {"auto_disable_bodies", "bool"},
    {"sor_pgs_precon_iters", "int"},   {"sor_pgs_iters", "int"},
    {"sor_pgs_w", "double"},           {"sor_pgs_rms_error_tol", "double"},
    {"contact_surface_layer", "double"}, {"contact_max_correcting_vel", "double"},
    {"cfm", "double"},                 {"erp", "double"},
    {"max_contacts", "int"},
};

dynamic_reconfigure::Config physicsConfig(const PhysicsProperties& p) {
  const gazebo_msgs::ODEPhysics o = odeConfig(p);
  dynamic_reconfigure::Config c;
  auto d = [&](const char* n, double v) {
    dynamic_reconfigure::DoubleParameter x;
    x.name = n;
    x.value = v;
    c.doubles.push_back(x);
  };
  auto i = [&](const char* n, int v) {
    dynamic_reconfigure::IntParameter x;
    x.name = n;
    x.value = v;
    c.ints.push_back(x);
  };
  d("time_step", p.time_step);
  d("max_update_rate", p.max_update_rate);
  d("gravity_x", p.gravity.x());
  d("gravity_y", p.gravity.y());
  d("gravity_z", p.gravity.z());
  dynamic_reconfigure::BoolParameter b;
  b.name = "auto_disable_bodies";
  b.value = o.auto_disable_bodies;
  c.bools.push_back(b);
  i("sor_pgs_precon_iters", static_cast<int>(o.sor_pgs_precon_iters));
  i("sor_pgs_iters", static_cast<int>(o.sor_pgs_iters));
  d("sor_pgs_w", o.sor_pgs_w);
  d("sor_pgs_rms_error_tol", o.sor_pgs_rms_error_tol);
  d("contact_surface_layer", o.contact_surface_layer);
  d("contact_max_correcting_vel", o.contact_max_correcting_vel);
  d("cfm", o.cfm);
  d("erp", o.erp);
  i("max_contacts", static_cast<int>(o.max_contacts));
  dynamic_reconfigure::GroupState g;
  g.name = "Default";
  g.state = true;
  g.id = 0;
  g.parent = 0;
  c.groups.push_back(g);
  return c;
}

}  // namespace

void GazeboInterface::advertiseProperties(ServiceAdvertiser<GazeboInterface>& serve,
                                          ros::NodeHandle& nh) {
  serve("get_joint_properties", &GazeboInterface::getJointProperties);
  serve("set_joint_properties", &GazeboInterface::setJointProperties);
  serve("get_physics_properties", &GazeboInterface::getPhysicsProperties);
  serve("set_physics_properties", &GazeboInterface::setPhysicsProperties);
  serve("get_light_properties", &GazeboInterface::getLightProperties);
  serve("set_light_properties", &GazeboInterface::setLightProperties);
  serve("delete_light", &GazeboInterface::deleteLight);
  serve("get_link_properties", &GazeboInterface::getLinkProperties);
  serve("set_link_properties", &GazeboInterface::setLinkProperties);
  serve("set_model_configuration", &GazeboInterface::setModelConfiguration);
  serve("apply_joint_effort", &GazeboInterface::applyJointEffort);
  serve("clear_joint_forces", &GazeboInterface::clearJointForces);
  // The physics as dynamic_reconfigure parameters, as gazebo_ros's reconfigure server in the
  // node's namespace offers them: set_parameters, parameter_descriptions, parameter_updates.
  serve("set_parameters", &GazeboInterface::setParameters);
  reconfigure_descriptions_pub_ =
      nh.advertise<dynamic_reconfigure::ConfigDescription>("parameter_descriptions", 1, true);
  reconfigure_updates_pub_ = nh.advertise<dynamic_reconfigure::Config>("parameter_updates", 1, true);
  dynamic_reconfigure::ConfigDescription description;
  dynamic_reconfigure::Group group;
  group.name = "Default";
  group.type = "";
  group.id = 0;
  group.parent = 0;
  for (const ReconfigureParam& p : kPhysicsParams) {
    dynamic_reconfigure::ParamDescription d;
    d.name = p.name;
    d.type = p.type;
    d.level = 0;
    group.parameters.push_back(d);
  }
  description.groups.push_back(group);
  description.dflt = physicsConfig(simulator_.properties().physicsProperties());
  description.max = description.dflt;
  description.min = description.dflt;
  for (auto& v : description.max.doubles) v.value = std::numeric_limits<double>::max();
  for (auto& v : description.min.doubles) v.value = -std::numeric_limits<double>::max();
  for (auto& v : description.max.ints) v.value = std::numeric_limits<int>::max();
  for (auto& v : description.min.ints) v.value = 0;
  reconfigure_descriptions_pub_.publish(description);
  publishPhysicsConfig();
}

void GazeboInterface::publishPhysicsConfig() {
  if (reconfigure_updates_pub_) reconfigure_updates_pub_.publish(physicsConfig(simulator_.properties().physicsProperties()));
}

// --- joints -----------------------------------------------------------------------------------

bool GazeboInterface::getJointProperties(gazebo_msgs::GetJointProperties::Request& req,
                                         gazebo_msgs::GetJointProperties::Response& res) {
  return answer(res, {"get_joint_properties: ", "", false}, [&] {
    const JointProperties j = simulator_.properties().jointProperties(req.joint_name);
    switch (j.info.type) {
      case JointType::kRevolute: res.type = res.REVOLUTE; break;
      case JointType::kContinuous: res.type = res.CONTINUOUS; break;
      case JointType::kPrismatic: res.type = res.PRISMATIC; break;
    }
    res.damping = {j.info.damping};
    res.position = {j.position};
    res.rate = {j.rate};
    return "GetJointProperties: got properties";
  });
}

bool GazeboInterface::setJointProperties(gazebo_msgs::SetJointProperties::Request& req,
                                         gazebo_msgs::SetJointProperties::Response& res) {
  const gazebo_msgs::ODEJointProperties& o = req.ode_joint_config;
  auto first = [](const std::vector<double>& v) {
    return v.empty() ? std::optional<double>() : std::optional<double>(v.front());
  };
  return answer(res, {"set_joint_properties: "}, [&] {
    // One-degree-of-freedom joints: the first entry of each list, as gazebo_ros's loop sets
    // axis 0 (a second entry names an axis we have not).
    for (const auto* v : {&o.damping, &o.hiStop, &o.loStop, &o.erp, &o.cfm, &o.stop_erp,
                          &o.stop_cfm, &o.fudge_factor, &o.fmax, &o.vel}) {
      if (v->size() > 1) {
        throw InputError("joint '" + req.joint_name + "': " + std::to_string(v->size()) +
                         " values for one axis (our joints have one degree of freedom)");
      }
    }
    for (const auto& [field, v] : {std::make_pair("erp", &o.erp), std::make_pair("cfm", &o.cfm),
                                    std::make_pair("stop_erp", &o.stop_erp),
                                    std::make_pair("stop_cfm", &o.stop_cfm),
                                    std::make_pair("fudge_factor", &o.fudge_factor)}) {
      if (!v->empty()) {
        throw InputError("joint '" + req.joint_name + "': " + field +
                         " is ODE's and has no counterpart in Bullet's joints; nothing set");
      }
    }
    JointPropertiesChange c;
    c.damping = first(o.damping);
    c.lower = first(o.loStop);
    c.upper = first(o.hiStop);
    c.velocity = first(o.vel);
    c.fmax = first(o.fmax);
    simulator_.properties().setJointProperties(req.joint_name, c);
    return "SetJointProperties: properties set";
  });
}

bool GazeboInterface::setModelConfiguration(gazebo_msgs::SetModelConfiguration::Request& req,
                                            gazebo_msgs::SetModelConfiguration::Response& res) {
  return answer(res, {}, [&] {
    simulator_.properties().setModelConfiguration(req.model_name, req.joint_names, req.joint_positions);
    return "SetModelConfiguration: success";
  });
}

bool GazeboInterface::applyJointEffort(gazebo_msgs::ApplyJointEffort::Request& req,
                                       gazebo_msgs::ApplyJointEffort::Response& res) {
  return answer(res, {"apply_joint_effort: "}, [&] {
    entities_.joint(req.joint_name);  // throws for an unknown joint
    if (!std::isfinite(req.effort) || std::fabs(req.effort) > 1e6) {
      throw InputError("joint '" + req.joint_name + "': effort " + std::to_string(req.effort) +
                       " is not finite or beyond 1e6 (N m or N)");
    }
    if (req.duration.toSec() == 0.0) throw InputError("duration 0: nothing applied");
    JointEffortJob job;
    job.joint = req.joint_name;
    job.effort = req.effort;
    job.start = std::max(req.start_time.toSec(), simulator_.time());  // gazebo_ros: a past start is now
    job.end = req.duration.toSec() < 0.0 ? -1.0 : job.start + std::max(req.duration.toSec(), simulator_.dt());
    joint_efforts_.push_back(job);
    return "ApplyJointEffort: effort set";
  });
}

bool GazeboInterface::clearJointForces(gazebo_msgs::JointRequest::Request& req,
                                       gazebo_msgs::JointRequest::Response&) {
  joint_efforts_.erase(std::remove_if(joint_efforts_.begin(), joint_efforts_.end(),
                                      [&](const JointEffortJob& j) { return j.joint == req.joint_name; }),
                       joint_efforts_.end());
  applyJointEfforts();
  return true;
}

void GazeboInterface::applyJointEfforts() {
  if (joint_efforts_.empty() && joints_pushed_.empty()) return;
  const double t = simulator_.time();
  // Sum per joint of the jobs due now (gazebo_ros's forceJointSchedulerSlot); a joint pushed in
  // the last step and not now goes back to 0.
  std::vector<std::pair<std::string, double>> due;
  for (const JointEffortJob& j : joint_efforts_) {
    if (t + 1e-9 < j.start) continue;
    if (j.end >= 0.0 && t + 1e-9 >= j.end) continue;
    auto it = std::find_if(due.begin(), due.end(), [&](const auto& d) { return d.first == j.joint; });
    if (it == due.end()) due.emplace_back(j.joint, j.effort);
    else it->second += j.effort;
  }
  joint_efforts_.erase(std::remove_if(joint_efforts_.begin(), joint_efforts_.end(),
                                      [&](const JointEffortJob& j) { return j.end >= 0.0 && t + 1e-9 >= j.end; }),
                       joint_efforts_.end());
  for (const std::string& name : joints_pushed_) {
    if (std::none_of(due.begin(), due.end(), [&](const auto& d) { return d.first == name; })) {
      due.emplace_back(name, 0.0);
    }
  }
  joints_pushed_.clear();
  for (const auto& [name, effort] : due) {
    try {
      const JointRef joint = entities_.joint(name);
      entities_.applyJointEffort(joint, effort);
      if (effort != 0.0) joints_pushed_.push_back(name);
    } catch (const InputError&) {
      // the model is gone since
    }
  }
}

// --- physics ----------------------------------------------------------------------------------

bool GazeboInterface::getPhysicsProperties(gazebo_msgs::GetPhysicsProperties::Request&,
                                           gazebo_msgs::GetPhysicsProperties::Response& res) {
  const PhysicsProperties p = simulator_.properties().physicsProperties();
  res.time_step = p.time_step;
  res.pause = simulator_.paused();
  res.max_update_rate = p.max_update_rate;
  tianracer_control::toXyzMsg(p.gravity, &res.gravity);
  res.ode_config = odeConfig(p);
  return succeeded(res, "GetPhysicsProperties: got properties");
}

bool GazeboInterface::setPhysicsProperties(gazebo_msgs::SetPhysicsProperties::Request& req,
                                           gazebo_msgs::SetPhysicsProperties::Response& res) {
  PhysicsProperties p = simulator_.properties().physicsProperties();
  p.time_step = req.time_step;
  p.max_update_rate = req.max_update_rate;
  p.gravity = Eigen::Vector3d(req.gravity.x, req.gravity.y, req.gravity.z);
  const std::string refused = applyOde(req.ode_config, &p);
  return answer(res, {"set_physics_properties: ", "; nothing changed"}, [&] {
    if (!refused.empty()) throw InputError("physics: " + refused);
    simulator_.properties().setPhysicsProperties(p);
    publishPhysicsConfig();
    return "physics engine updated";
  });
}

bool GazeboInterface::setParameters(dynamic_reconfigure::Reconfigure::Request& req,
                                    dynamic_reconfigure::Reconfigure::Response& res) {
  PhysicsProperties p = simulator_.properties().physicsProperties();
  gazebo_msgs::ODEPhysics o = odeConfig(p);
  std::string refused;
  for (const auto& d : req.config.doubles) {
    if (d.name == "time_step") p.time_step = d.value;
    else if (d.name == "max_update_rate") p.max_update_rate = d.value;
    else if (d.name == "gravity_x") p.gravity.x() = d.value;
    else if (d.name == "gravity_y") p.gravity.y() = d.value;
    else if (d.name == "gravity_z") p.gravity.z() = d.value;
    else if (d.name == "sor_pgs_w") o.sor_pgs_w = d.value;
    else if (d.name == "sor_pgs_rms_error_tol") o.sor_pgs_rms_error_tol = d.value;
    else if (d.name == "contact_surface_layer") o.contact_surface_layer = d.value;
    else if (d.name == "contact_max_correcting_vel") o.contact_max_correcting_vel = d.value;
    else if (d.name == "cfm") o.cfm = d.value;
    else if (d.name == "erp") o.erp = d.value;
    else refused = "unknown parameter '" + d.name + "'";
  }
  for (const auto& i : req.config.ints) {
    if (i.name == "sor_pgs_precon_iters") o.sor_pgs_precon_iters = static_cast<std::uint32_t>(i.value);
    else if (i.name == "sor_pgs_iters") o.sor_pgs_iters = static_cast<std::uint32_t>(std::max(0, i.value));
    else if (i.name == "max_contacts") o.max_contacts = static_cast<std::uint32_t>(i.value);
    else refused = "unknown parameter '" + i.name + "'";
  }
  for (const auto& b : req.config.bools) {
    if (b.name == "auto_disable_bodies") o.auto_disable_bodies = b.value;
    else refused = "unknown parameter '" + b.name + "'";
  }
  if (refused.empty()) refused = applyOde(o, &p);
  try {
    if (!refused.empty()) throw InputError("physics: " + refused);
    simulator_.properties().setPhysicsProperties(p);
  } catch (const InputError& e) {
    ROS_WARN_STREAM("set_parameters: " << e.what() << "; nothing changed");
  }
  res.config = physicsConfig(simulator_.properties().physicsProperties());
  publishPhysicsConfig();
  return true;
}

}  // namespace tianracer_sim
