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

EntityState stateFromMsg(const geometry_msgs::Pose& pose, const geometry_msgs::Twist& twist,
                         bool* ok) {
  EntityState s;
  *ok = fromPose(pose, &s.X_WE) && fromTwistMsg(twist, &s.V_WE);
  return s;
}

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
    : simulator_(sim), sim_(sim.simulation()), world_(sim.world()), options_(options),
      spawner_(spawner), after_reset_(std::move(after_reset)) {
  if (!(options_.states_rate >= 0.0) || !std::isfinite(options_.states_rate)) {
    throw std::runtime_error("parameter ~gazebo_states_rate must be >= 0 (0 = every step), got " +
                             std::to_string(options_.states_rate));
  }
  period_ = options_.states_rate > 0.0 ? 1.0 / options_.states_rate : 0.0;
  // The node publishes its ground truth at the start time; these first come a period later,
  // then on the same steps.
  next_ = sim_.time() + period_;
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

bool GazeboInterface::resolve(const std::string& name, bool allow_model, Entity* e,
                              std::string* error) const {
  const ScopedName n = splitScopedName(name);
  *e = Entity();
  e->model_name = n.model;
  e->link = n.link;
  if (n.model.empty()) {
    *error = "'" + name + "' names no model (use \"model\" or \"model::link\")";
    return false;
  }
  if (n.link.empty() && !allow_model) {
    *error = "'" + name + "' is not a link: use gazebo's scoped name \"model::link\"";
    return false;
  }
  if (SimRobot* robot = sim_.findRobot(n.model)) {
    e->robot = robot;
    if (!n.link.empty() && !robot->model.urdf->getLink(n.link)) {
      *error = "model '" + n.model + "' has no link '" + n.link + "'";
      return false;
    }
    return true;
  }
  if (world_.ground_plane && n.model == "ground_plane") {
    e->ground_plane = true;
    if (!n.link.empty() && n.link != "link") {
      *error = "model 'ground_plane' has no link '" + n.link + "' (its one link is 'link')";
      return false;
    }
    return true;
  }
  for (const ModelDescription& m : world_.models) {
    if (m.name != n.model) continue;
    e->model = &m;
    if (const int i = sim_.physics().freeBodyIndex(m.name); i >= 0) {
      e->free = &sim_.physics().freeBody(i);
    }
    if (!n.link.empty() &&
        std::none_of(m.links.begin(), m.links.end(),
                     [&](const LinkDescription& l) { return l.name == n.link; })) {
      *error = "model '" + n.model + "' has no link '" + n.link + "'";
      return false;
    }
    return true;
  }
  std::string known;
  for (const std::string& m : modelNames()) known += (known.empty() ? "" : ", ") + m;
  *error = "no model named '" + n.model + "' (models: " + known + ")";
  return false;
}

PhysicsRobot* GazeboInterface::physicsOf(const Entity& e) const {
  if (e.robot) return &sim_.physics().robot(e.robot->id);
  return e.free;
}

EntityState GazeboInterface::stateOf(const Entity& e) const {
  EntityState s;
  if (const PhysicsRobot* body = physicsOf(e)) {
    const PhysicsRobot& pr = *body;
    if (e.link.empty()) {
      s.X_WE = pr.basePose();
      s.V_WE = pr.baseTwist();
    } else {
      s.X_WE = pr.linkPose(e.link);
      s.V_WE = pr.linkTwist(e.link);
    }
  } else if (e.ground_plane) {
    s.X_WE = world_.X_WG;
  } else if (e.model) {
    s.X_WE = e.model->X_WM;
    if (!e.link.empty()) {
      for (const LinkDescription& l : e.model->links) {
        if (l.name == e.link) s.X_WE = e.model->X_WM * l.X_ML;
      }
    }
  }
  return s;
}

bool GazeboInterface::frameState(const std::string& name, EntityState* frame,
                                 std::string* error) const {
  if (isWorldFrame(name)) {
    *frame = EntityState();
    return true;
  }
  Entity e;
  if (!resolve(name, true, &e, error)) {
    *error = "reference_frame: " + *error;
    return false;
  }
  *frame = stateOf(e);
  return true;
}

GazeboInterface::Target GazeboInterface::target(const std::string& name, bool allow_model,
                                                const std::string& reference_frame) const {
  Target t;
  t.ok = resolve(name, allow_model, &t.entity, &t.error) &&
         frameState(reference_frame, &t.frame, &t.error);
  return t;
}

std::vector<std::string> GazeboInterface::modelNames() const {
  std::vector<std::string> names;
  if (world_.ground_plane) names.push_back("ground_plane");
  for (const ModelDescription& m : world_.models) names.push_back(m.name);
  for (const auto& r : const_cast<Simulation&>(sim_).robots()) names.push_back(r->name);
  return names;
}

bool GazeboInterface::setBase(PhysicsRobot* body, const EntityState& s, bool stop_joints,
                              std::string* error) {
  if (const std::string bad = checkModelState(s.X_WE, s.V_WE); !bad.empty()) {
    *error = bad;
    return false;
  }
  PhysicsRobot& pr = *body;
  pr.setBasePose(s.X_WE);
  if (stop_joints) {
    pr.setModelTwist(s.V_WE);
  } else {
    pr.setBaseTwist(s.V_WE);
  }
  return true;
}

// --- model and link states ----------------------------------------------------------------------

bool GazeboInterface::getModelState(gazebo_msgs::GetModelState::Request& req,
                                    gazebo_msgs::GetModelState::Response& res) {
  res.header.stamp = ros::Time(sim_.time());
  res.header.frame_id = req.relative_entity_name;
  res.success = false;
  const Target t = target(req.model_name, true, req.relative_entity_name);
  if (!t.ok) {
    res.status_message = "get_model_state: " + t.error;
    return true;
  }
  if (!t.entity.link.empty()) {
    res.status_message = "get_model_state: '" + req.model_name +
                         "' is a link; use get_link_state or the model's name";
    return true;
  }
  const EntityState s = relativeTo(stateOf(t.entity), t.frame);
  res.pose = toPose(s.X_WE);
  res.twist = toTwistMsg(s.V_WE);
  return succeeded(res, "GetModelState: got properties");
}

bool GazeboInterface::setModelState(gazebo_msgs::SetModelState::Request& req,
                                    gazebo_msgs::SetModelState::Response& res) {
  const gazebo_msgs::ModelState& m = req.model_state;
  return answer(res, {"set_model_state: "}, [&] {
    const Target t = target(m.model_name, true, m.reference_frame);
    if (!t.ok) throw InputError(t.error);
    if (!t.entity.link.empty())
      throw InputError("'" + m.model_name + "' is a link; use set_link_state");
    if (!physicsOf(t.entity))
      throw InputError("model '" + m.model_name + "' is static and cannot be moved");
    EntityState in_frame;
    if (!fromPose(m.pose, &in_frame.X_WE)) {
      throw InputError("pose of '" + m.model_name +
                       "' is not finite or has a zero quaternion; state unchanged");
    }
    if (!fromTwistMsg(m.twist, &in_frame.V_WE))
      throw InputError("twist of '" + m.model_name + "' is not finite; state unchanged");
    std::string error;
    if (!setBase(physicsOf(t.entity), fromFrame(in_frame, t.frame), true, &error))
      throw InputError(error + " for '" + m.model_name + "'; state unchanged");
    return "SetModelState: set model state done";
  });
}

bool GazeboInterface::getLinkState(gazebo_msgs::GetLinkState::Request& req,
                                   gazebo_msgs::GetLinkState::Response& res) {
  res.success = false;
  res.link_state.link_name = req.link_name;
  res.link_state.reference_frame = req.reference_frame;
  const Target t = target(req.link_name, false, req.reference_frame);
  if (!t.ok) {
    res.status_message = "get_link_state: " + t.error;
    return true;
  }
  const EntityState s = relativeTo(stateOf(t.entity), t.frame);
  res.link_state.pose = toPose(s.X_WE);
  res.link_state.twist = toTwistMsg(s.V_WE);
  return succeeded(res, "GetLinkState: got state");
}

bool GazeboInterface::setLinkState(gazebo_msgs::SetLinkState::Request& req,
                                   gazebo_msgs::SetLinkState::Response& res) {
  const gazebo_msgs::LinkState& l = req.link_state;
  bool finite = false;
  const EntityState in_frame = stateFromMsg(l.pose, l.twist, &finite);
  return answer(res, {"set_link_state: "}, [&] {
    const Target t = target(l.link_name, false, l.reference_frame);
    if (!t.ok) throw InputError(t.error);
    if (!physicsOf(t.entity))
      throw InputError("'" + l.link_name + "' belongs to a static model and cannot be moved");
    if (!finite) {
      throw InputError("pose or twist of '" + l.link_name +
                       "' is not finite or has a zero quaternion; state unchanged");
    }
    // The whole robot moves rigidly so that the link gets the state (joints kept): gazebo
    // moves the one link and lets the joints pull the others after it.
    const PhysicsRobot& pr = *physicsOf(t.entity);
    const EntityState L = fromFrame(in_frame, t.frame);
    const Eigen::Isometry3d X_LB = pr.linkPose(t.entity.link).inverse() * pr.basePose();
    EntityState B;
    B.X_WE = L.X_WE * X_LB;
    B.V_WE = shiftTwist(L.V_WE, L.X_WE.translation(), B.X_WE.translation());
    std::string error;
    if (!setBase(physicsOf(t.entity), B, false, &error)) {
      throw InputError(error + " for '" + l.link_name + "' (its model's base); state unchanged");
    }
    return "SetLinkState: success";
  });
}

void GazeboInterface::onModelStateTopic(const gazebo_msgs::ModelState::ConstPtr& msg) {
  gazebo_msgs::SetModelState::Request req;
  gazebo_msgs::SetModelState::Response res;
  req.model_state = *msg;
  setModelState(req, res);  // a failure is logged there
}

void GazeboInterface::onLinkStateTopic(const gazebo_msgs::LinkState::ConstPtr& msg) {
  gazebo_msgs::SetLinkState::Request req;
  gazebo_msgs::SetLinkState::Response res;
  req.link_state = *msg;
  setLinkState(req, res);
}

// --- properties ---------------------------------------------------------------------------------

bool GazeboInterface::getModelProperties(gazebo_msgs::GetModelProperties::Request& req,
                                         gazebo_msgs::GetModelProperties::Response& res) {
  res.success = false;
  Entity e;
  std::string error;
  if (!resolve(req.model_name, true, &e, &error) || !e.link.empty()) {
    res.status_message = "get_model_properties: " +
                         (error.empty() ? "'" + req.model_name + "' is a link, not a model" : error);
    return true;
  }
  if (e.robot) {
    // Bodies as Gazebo's URDF import makes them: links joined by fixed joints are lumped into
    // their parent, and the lumped collisions are named <parent>_fixed_joint_lump__<link>_collision.
    const PhysicsRobot& pr = sim_.physics().robot(e.robot->id);
    for (const TreeBody& b : pr.tree().bodies) {
      res.body_names.push_back(b.link);
      std::map<std::string, int> count;
      for (const CollisionGeometry& c : b.collisions) {
        std::string name = c.link == b.link ? c.link + "_collision"
                                             : b.link + "_fixed_joint_lump__" + c.link + "_collision";
        const int k = count[name]++;
        if (k > 0) name += "_" + std::to_string(k);
        res.geom_names.push_back(name);
      }
    }
    for (const JointInfo& j : pr.joints()) res.joint_names.push_back(j.name);
    res.canonical_body_name = pr.tree().bodies.front().link;
    res.is_static = false;
  } else if (e.ground_plane) {
    res.body_names = {"link"};
    res.geom_names = {"collision"};
    res.canonical_body_name = "link";
    res.is_static = true;
  } else {
    for (const LinkDescription& l : e.model->links) {
      res.body_names.push_back(l.name);
      for (const CollisionDescription& c : l.collisions) res.geom_names.push_back(c.name);
    }
    if (!e.model->links.empty()) res.canonical_body_name = e.model->links.front().name;
    res.is_static = e.free == nullptr;
  }
  return succeeded(res, "GetModelProperties: got properties");
}

bool GazeboInterface::getWorldProperties(gazebo_msgs::GetWorldProperties::Request&,
                                         gazebo_msgs::GetWorldProperties::Response& res) {
  res.sim_time = sim_.time();
  res.model_names = modelNames();
  res.rendering_enabled = true;
  return succeeded(res, "GetWorldProperties: got properties");
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
  } else if (!physicsOf(t.entity)) {
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
    if (!wrenches_.add(s, sim_.time(), req.duration.toSec(), sim_.dt())) {
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
  Entity e;
  std::string error;
  if (!resolve(req.body_name, false, &e, &error)) {
    ROS_WARN_STREAM("clear_body_wrenches: " << error);
    return true;
  }
  wrenches_.clear(e.model_name + "::" + e.link);
  return true;
}

// --- stepping -----------------------------------------------------------------------------------

void GazeboInterface::beforeStep() {
  applyJointEfforts();
  if (wrenches_.empty()) return;
  for (const WrenchSchedule::Total& w : wrenches_.totals(sim_.time())) {
    Entity e;
    std::string error;
    if (!resolve(w.body, false, &e, &error) || !physicsOf(e)) continue;  // gone since
    physicsOf(e)->setExternalWrench(e.link, w.force_W, w.torque_W);
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
  for (const std::string& m : modelNames()) {
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
  std::string error;
  if (!frameState(req.reference_frame, &frame, &error)) return fail(error);
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
  Entity e;
  std::string error;
  if (req.model_name.find("::") != std::string::npos) {
    error = "'" + req.model_name + "' is a link; delete_model takes a model name";
  } else if (resolve(req.model_name, true, &e, &error)) {
    try {
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
  next_ = sim_.time();
}

void GazeboInterface::rebuildStateMessages() {
  model_states_.name.clear();
  model_states_.pose.clear();
  model_slots_.clear();
  link_states_.name.clear();
  link_states_.pose.clear();
  link_slots_.clear();
  auto add_model = [&](const std::string& name, const PhysicsRobot* body,
                       const Eigen::Isometry3d& X_WM) {
    model_states_.name.push_back(name);
    model_slots_.push_back({body, ""});
    model_states_.pose.push_back(toPose(X_WM));
  };
  auto add_link = [&](const std::string& name, const PhysicsRobot* body, const std::string& link,
                      const Eigen::Isometry3d& X_WL) {
    link_states_.name.push_back(name);
    link_slots_.push_back({body, link});
    link_states_.pose.push_back(toPose(X_WL));
  };
  if (world_.ground_plane) {
    add_model("ground_plane", nullptr, world_.X_WG);
    add_link("ground_plane::link", nullptr, "", world_.X_WG);
  }
  for (const ModelDescription& m : world_.models) {
    const int free = sim_.physics().freeBodyIndex(m.name);
    const PhysicsRobot* body = free >= 0 ? &sim_.physics().freeBody(free) : nullptr;
    add_model(m.name, body, m.X_WM);
    // Every link, as Gazebo lists a world model's links (each moves on its own).
    for (const LinkDescription& l : m.links) add_link(m.name + "::" + l.name, body, l.name, m.X_WM * l.X_ML);
  }
  for (const auto& robot : sim_.robots()) {
    const PhysicsRobot* body = &sim_.physics().robot(robot->id);
    add_model(robot->name, body, Eigen::Isometry3d::Identity());
    // One entry per rigid body, named after its first link: what Gazebo lists after lumping
    // the links joined by fixed joints.
    for (const TreeBody& b : body->tree().bodies) {
      add_link(robot->name + "::" + b.link, body, b.link, Eigen::Isometry3d::Identity());
    }
  }
  model_states_.twist.assign(model_states_.name.size(), geometry_msgs::Twist());
  link_states_.twist.assign(link_states_.name.size(), geometry_msgs::Twist());
  robots_in_msgs_ = sim_.robots().size();
}

void GazeboInterface::afterStep() {
  // The ground truth's schedule (sim_node's Schedule): a fixed grid, restarted after a pause
  // or reset rather than bursting to catch up.
  const double t = sim_.time();
  if (t + 1e-9 < next_) return;
  if (period_ > 0.0) {
    next_ += period_;
    if (next_ <= t) next_ = t + period_;
  } else {
    next_ = t;
  }
  const bool want_models = model_states_pub_.getNumSubscribers() > 0;
  const bool want_links = link_states_pub_.getNumSubscribers() > 0;
  if (!want_models && !want_links) return;
  if (robots_in_msgs_ != sim_.robots().size()) rebuildStateMessages();
  if (want_models) {
    for (std::size_t i = 0; i < model_slots_.size(); ++i) {
      const Slot& s = model_slots_[i];
      if (!s.body) continue;
      model_states_.pose[i] = toPose(s.body->basePose());
      model_states_.twist[i] = toTwistMsg(s.body->baseTwist());
    }
    model_states_pub_.publish(model_states_);
  }
  if (want_links) {
    for (std::size_t i = 0; i < link_slots_.size(); ++i) {
      const Slot& s = link_slots_[i];
      if (!s.body) continue;
      link_states_.pose[i] = toPose(s.body->linkPose(s.link));
      link_states_.twist[i] = toTwistMsg(s.body->linkTwist(s.link));
    }
    link_states_pub_.publish(link_states_);
  }
}

}  // namespace tianracer_sim
