#include "tianracer_sim/ros/gazebo_interface.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <tinyxml2.h>

#include "gazebo_answer.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {

namespace {

/// Bound on an external force / torque: beyond it one step throws a 1 kg body at 1 km/s.
constexpr double kMaxWrench = 1e6;  // N, N m

bool finiteVec(const geometry_msgs::Vector3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string fmt(const geometry_msgs::Vector3& v) {
  std::ostringstream o;
  o << "(" << v.x << ", " << v.y << ", " << v.z << ")";
  return o.str();
}

Eigen::Vector3d vec(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

void addRobotNamespace(tinyxml2::XMLElement* e, const std::string& ns) {
  for (tinyxml2::XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::string(c->Name()) == "plugin" && !c->FirstChildElement("robotNamespace")) {
      c->InsertNewChildElement("robotNamespace")->SetText(ns.c_str());
    }
    addRobotNamespace(c, ns);
  }
}

}  // namespace

std::string withRobotNamespace(const std::string& urdf, const std::string& robot_namespace) {
  tinyxml2::XMLDocument doc;
  if (doc.Parse(urdf.data(), urdf.size()) != tinyxml2::XML_SUCCESS) {
    throw std::runtime_error("model_xml:" + std::to_string(doc.ErrorLineNum()) +
                             ": malformed XML: " + doc.ErrorName());
  }
  if (robot_namespace.empty()) return urdf;
  addRobotNamespace(doc.RootElement(), robot_namespace);
  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  return printer.CStr();
}

GazeboInterface::GazeboInterface(ros::NodeHandle nh, Simulator& sim, const Options& options,
                                 ModelSpawner* spawner, std::function<void()> after_reset)
    : simulator_(sim), entities_(sim.entities()), world_(sim.world()), options_(options),
      spawner_(spawner), after_reset_(std::move(after_reset)) {
  if (!(options_.states_rate >= 0.0) || !std::isfinite(options_.states_rate)) {
    throw std::runtime_error("parameter ~gazebo_states_rate must be >= 0 (0 = every step), got " +
                             std::to_string(options_.states_rate));
  }
  period_ = options_.states_rate > 0.0 ? 1.0 / options_.states_rate : 0.0;
  // The node publishes its ground truth at the start time; these first come a period later,
  // then on the same steps.
  next_ = simulator_.time() + period_;
  if (!options_.enable_ros_network) {
    // gazebo_ros_api_plugin.cpp, advertiseServices(): only /clock (the owner's) remains.
    ROS_INFO("ROS gazebo topics/services are disabled (~enable_ros_network false)");
    return;
  }
  model_states_pub_ = nh.advertise<gazebo_msgs::ModelStates>("model_states", 1);
  link_states_pub_ = nh.advertise<gazebo_msgs::LinkStates>("link_states", 1);
  set_model_state_sub_ =
      nh.subscribe("set_model_state", 10, &GazeboInterface::onModelStateTopic, this);
  set_link_state_sub_ = nh.subscribe("set_link_state", 10, &GazeboInterface::onLinkStateTopic, this);
  ServiceAdvertiser<GazeboInterface> serve(nh, this, &services_);
  serve("get_model_state", &GazeboInterface::getModelState);
  serve("set_model_state", &GazeboInterface::setModelState);
  serve("get_link_state", &GazeboInterface::getLinkState);
  serve("set_link_state", &GazeboInterface::setLinkState);
  serve("get_model_properties", &GazeboInterface::getModelProperties);
  serve("get_world_properties", &GazeboInterface::getWorldProperties);
  serve("apply_body_wrench", &GazeboInterface::applyBodyWrench);
  serve("clear_body_wrenches", &GazeboInterface::clearBodyWrenches);
  serve("pause_physics", &GazeboInterface::pausePhysics);
  serve("unpause_physics", &GazeboInterface::unpausePhysics);
  serve("reset_simulation", &GazeboInterface::resetSimulation);
  serve("reset_world", &GazeboInterface::resetWorld);
  if (spawner_) {
    serve("spawn_urdf_model", &GazeboInterface::spawnUrdfModel);
    serve("spawn_sdf_model", &GazeboInterface::spawnSdfModel);
    serve("delete_model", &GazeboInterface::deleteModel);
  }
  advertiseProperties(serve, nh);
  ROS_INFO("%s and %s at %g Hz (sim time)%s", model_states_pub_.getTopic().c_str(),
           link_states_pub_.getTopic().c_str(), options_.states_rate,
           options_.states_rate > 0.0 ? "" : " (every step)");
}

// --- entities ---------------------------------------------------------------------------------

GazeboInterface::Target GazeboInterface::target(const std::string& name, bool allow_model,
                                                const std::string& reference_frame) const {
  Target t;
  try {
    t.entity = entities_.find(name, allow_model);
    t.frame = entities_.frame(reference_frame);
    t.ok = true;
  } catch (const InputError& e) {
    t.error = e.what();
  }
  return t;
}

// --- wrenches -----------------------------------------------------------------------------------

bool GazeboInterface::applyBodyWrench(gazebo_msgs::ApplyBodyWrench::Request& req,
                                      gazebo_msgs::ApplyBodyWrench::Response& res) {
  res.success = false;
  const auto& w = req.wrench;
  const auto& p = req.reference_point;
  const Target t = target(req.body_name, false, req.reference_frame);
  if (!t.ok) {
    res.status_message = "apply_body_wrench: " + t.error;
  } else if (!t.entity.body) {
    res.status_message = "apply_body_wrench: '" + req.body_name +
                         "' belongs to a static model: nothing to push";
  } else if (!finiteVec(w.force) || !finiteVec(w.torque) || !std::isfinite(p.x) ||
             !std::isfinite(p.y) || !std::isfinite(p.z)) {
    res.status_message = "apply_body_wrench: force " + fmt(w.force) + ", torque " +
                         fmt(w.torque) + " or reference_point is not finite; nothing applied";
  } else if (vec(w.force).cwiseAbs().maxCoeff() > kMaxWrench ||
             vec(w.torque).cwiseAbs().maxCoeff() > kMaxWrench) {
    res.status_message = "apply_body_wrench: force " + fmt(w.force) + " or torque " +
                         fmt(w.torque) + " is out of range (each component <= 1e6 N, N m)";
  } else {
    // gazebo_ros: the force acts through the body's centre of mass; a reference point adds
    // p x F to the torque; both are turned from the reference frame into the world once, now.
    const Eigen::Vector3d F = vec(w.force);
    const Eigen::Vector3d tau = vec(w.torque) + Eigen::Vector3d(p.x, p.y, p.z).cross(F);
    ScheduledWrench s;
    s.body = t.entity.model_name + "::" + t.entity.link;
    s.force_W = t.frame.X_WE.linear() * F;
    s.torque_W = t.frame.X_WE.linear() * tau;
    s.start = req.start_time.toSec();
    if (!wrenches_.add(s, simulator_.time(), req.duration.toSec(), simulator_.dt())) {
      res.status_message = "apply_body_wrench: duration 0: nothing applied";
    } else {
      res.success = true;
      res.status_message = "";
    }
  }
  if (!res.success && !res.status_message.empty()) ROS_WARN_STREAM(res.status_message);
  return true;
}

bool GazeboInterface::clearBodyWrenches(gazebo_msgs::BodyRequest::Request& req,
                                        gazebo_msgs::BodyRequest::Response&) {
  try {
    const Entity e = entities_.find(req.body_name, false);
    wrenches_.clear(e.model_name + "::" + e.link);
  } catch (const InputError& error) {
    ROS_WARN_STREAM("clear_body_wrenches: " << error.what());
  }
  return true;
}

// --- stepping -----------------------------------------------------------------------------------

void GazeboInterface::beforeStep() {
  applyJointEfforts();
  if (wrenches_.empty()) return;
  for (const WrenchSchedule::Total& w : wrenches_.totals(simulator_.time())) {
    Entity e;
    try {
      e = entities_.find(w.body, false);
    } catch (const InputError&) {
      continue;  // gone since
    }
    entities_.applyWrench(e, w.force_W, w.torque_W);
  }
}

// --- spawn and delete ---------------------------------------------------------------------------

bool GazeboInterface::spawnUrdfModel(gazebo_msgs::SpawnModel::Request& req,
                                     gazebo_msgs::SpawnModel::Response& res) {
  return spawn("spawn_urdf_model", req, res);
}

bool GazeboInterface::spawnSdfModel(gazebo_msgs::SpawnModel::Request& req,
                                    gazebo_msgs::SpawnModel::Response& res) {
  return spawn("spawn_sdf_model", req, res);
}

bool GazeboInterface::spawn(const std::string& service, gazebo_msgs::SpawnModel::Request& req,
                            gazebo_msgs::SpawnModel::Response& res) {
  res.success = false;
  auto fail = [&](const std::string& why) {
    res.status_message = service + ": model '" + req.model_name + "': " + why;
    ROS_ERROR_STREAM(res.status_message);
    return true;
  };
  if (req.model_name.empty()) return fail("model_name is empty");
  if (req.model_name.find("::") != std::string::npos)
    return fail("a model name cannot contain '::' (it separates model and link)");
  for (const std::string& m : entities_.modelNames()) {
    if (m == req.model_name) return fail("a model of that name exists already; delete it first");
  }
  // Where the model goes: initial_pose in reference_frame. An all-zero quaternion (a default
  // Pose message) is the identity, as in gazebo_ros, whose quaternion normalises it so.
  geometry_msgs::Pose pose = req.initial_pose;
  const auto& q = pose.orientation;
  if (q.x == 0.0 && q.y == 0.0 && q.z == 0.0 && q.w == 0.0) pose.orientation.w = 1.0;
  Eigen::Isometry3d X_FM;
  if (!fromPose(pose, &X_FM)) return fail("initial_pose is not finite");
  EntityState frame;
  try {
    frame = entities_.frame(req.reference_frame);
  } catch (const InputError& e) {
    return fail(e.what());
  }
  const Eigen::Isometry3d X_WM = frame.X_WE * X_FM;
  if (const std::string bad = checkModelState(X_WM, Twist()); !bad.empty())
    return fail("initial_pose: " + bad);
  // The root element decides, as the XML says what it is whichever service carried it.
  if (req.model_xml.find_first_not_of(" \t\r\n") == std::string::npos)
    return fail("model_xml is empty");
  tinyxml2::XMLDocument doc;
  if (parseXmlDocument(req.model_xml, &doc) != tinyxml2::XML_SUCCESS) {
    return fail("model_xml:" + std::to_string(doc.ErrorLineNum()) + ": malformed XML: " +
                doc.ErrorName());
  }
  const bool urdf = std::string(doc.RootElement()->Name()) == "robot";
  try {
    if (urdf) {
      spawner_->spawnRobot(req.model_name, withRobotNamespace(req.model_xml, req.robot_namespace),
                           X_WM);
    } else {
      spawner_->spawnWorldModel(req.model_name, req.model_xml, X_WM);
    }
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  onModelsChanged();
  res.success = true;
  res.status_message = service + ": model '" + req.model_name + "' spawned";
  ROS_INFO_STREAM(res.status_message);
  return true;
}

bool GazeboInterface::deleteModel(gazebo_msgs::DeleteModel::Request& req,
                                  gazebo_msgs::DeleteModel::Response& res) {
  res.success = false;
  std::string error;
  if (req.model_name.find("::") != std::string::npos) {
    error = "'" + req.model_name + "' is a link; delete_model takes a model name";
  } else {
    try {
      entities_.find(req.model_name, true);
      spawner_->deleteModel(req.model_name);
      onModelsChanged();
      res.success = true;
      res.status_message = "delete_model: model '" + req.model_name + "' deleted";
      ROS_INFO_STREAM(res.status_message);
      return true;
    } catch (const std::exception& ex) {
      error = ex.what();
    }
  }
  res.status_message = "delete_model: " + error;
  ROS_ERROR_STREAM(res.status_message);
  return true;
}

// --- pause and reset -----------------------------------------------------------------------------

bool GazeboInterface::pausePhysics(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  simulator_.setPaused(true);
  return true;
}

bool GazeboInterface::unpausePhysics(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  simulator_.setPaused(false);
  return true;
}

bool GazeboInterface::resetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  simulator_.resetSimulation();
  onReset();
  if (after_reset_) after_reset_();
  return true;
}

bool GazeboInterface::resetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  simulator_.resetWorld();
  onReset();
  return true;
}

void GazeboInterface::onReset() {
  wrenches_.clear();
  joint_efforts_.clear();
  beforeStep();  // switches the forces off
  next_ = simulator_.time();
}

}  // namespace tianracer_sim
