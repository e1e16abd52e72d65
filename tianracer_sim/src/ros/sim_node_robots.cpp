// The sim node's robots and models: from the node's parameters at start-up and from
// spawn_urdf_model / spawn_sdf_model at run time, both through setUpRobot() (the one robot
// set-up, simulator/robot_setup.h, on the parameter server) and addRobot() (the Simulator's
// addRobot plus the robot's bridges); delete_model takes everything back out. The spawner calls
// come from GazeboInterface on the node's callback thread, between steps.
#include <algorithm>

#include <ros/package.h>

#include <tianracer_control/ros/controller_adapter.h>

#include "tianracer_sim/ros/controller_params.h"
#include "tianracer_sim/ros/params.h"
#include "tianracer_sim/ros/plugins/sensor_publisher.h"
#include "tianracer_sim/ros/sim_node.h"

namespace tianracer_sim {

namespace {

LoadOptions loadOptions(const ros::NodeHandle& rp) {
  LoadOptions options;
  options.resolver.find_package = [](const std::string& pkg) { return ros::package::getPath(pkg); };
  // Relative mesh URIs of a robot_description filled from a file resolve against its folder.
  rp.param<std::string>("model_dir", options.resolver.base_dir, "");
  return options;
}

/// gazebo_ros_control's parameters under the robot's namespace (DefaultRobotHWSim initSim:
/// joint_limits/<joint>, gazebo_ros_control/pid_gains/<joint>; SteerBotHardwareGazebo's).
RobotHwSimParams readRobotHwSimParams(const std::string& ns) {
  RobotHwSimParams p;
  ros::NodeHandle nh(ns);
  p.ns = nh.getNamespace();
  XmlRpc::XmlRpcValue v;
  if (nh.getParam("joint_limits", v)) p.joint_limits = tianracer_control::toParamValue(v);
  if (nh.getParam("gazebo_ros_control/pid_gains", v))
    p.pid_gains = tianracer_control::toParamValue(v);
  // SteerBotHardwareGazebo's (sim/steer_bot_hw_sim.h).
  if (nh.getParam("steer_bot_hardware_gazebo", v))
    p.steer_bot_hardware_gazebo = tianracer_control::toParamValue(v);
  if (nh.getParam("gains", v)) p.gains = tianracer_control::toParamValue(v);
  return p;
}

}  // namespace

void SimNode::loadRobot(const ros::NodeHandle& rp, const std::string& fixed_name) {
  LoadOptions options = loadOptions(rp);
  options.warn = [](const std::string& w) { warnOnce(w); };
  std::string model_file;
  rp.param<std::string>("model", model_file, "");
  RobotModel model;
  if (!model_file.empty()) {
    model = loadRobotModelFile(model_file, options);
  } else {
    std::string param;
    rp.param<std::string>("robot_param", param, "robot_description");
    std::string urdf;
    if (!nh_.getParam(param, urdf)) {
      throw ModelError("parameter " + nh_.resolveName(param) +
                       " is not set: load the URDF (e.g. with xacro), give ~model, or set "
                       "~robots to an empty list for the world alone");
    }
    if (urdf.find_first_not_of(" \t\r\n") == std::string::npos) {
      throw ModelError("parameter " + nh_.resolveName(param) + " (robot_description) is empty");
    }
    model = loadRobotModel(urdf, nh_.resolveName(param), options);
  }

  const RobotSetup setup = setUpRobot(model, fixed_name, false, rp);
  bool auto_z = true;
  const Eigen::Isometry3d X_WB = getSpawnPose(rp, &auto_z);
  startupMark("robot '" + setup.name + "': URDF and meshes");
  addRobot(std::move(model), setup, X_WB, auto_z, rp);
  startupMark("robot '" + setup.name + "': physics, controllers, sensors (GL context), topics");
}

RobotSetup SimNode::setUpRobot(const RobotModel& model, const std::string& spawn_name,
                               bool spawned, const ros::NodeHandle& rp) {
  RobotSetupRequest request;
  request.spawn_name = spawn_name;
  rp.param<std::string>("robot_name", request.robot_name, "");
  std::string control_ns;
  if (rp.getParam("control_namespace", control_ns)) request.control_namespace = control_ns;
  bool given = false;
  const std::vector<std::string> listed = getNameList(rp, "controllers", &given);
  if (given) request.controllers = listed;
  rp.param<std::string>("control_config", request.control_config, "");
  request.waits_for_spawner = spawned && !request.control_namespace;
  RobotSetup setup = tianracer_sim::setUpRobot(model, request, RosControlParams());
  for (const std::string& note : setup.notes) ROS_INFO_STREAM(note);
  for (const std::string& warning : setup.warnings) ROS_WARN_STREAM(warning);
  return setup;
}

void SimNode::addRobot(RobotModel model, const RobotSetup& setup, const Eigen::Isometry3d& X_WB,
                       bool auto_z, const ros::NodeHandle& rp) {
  const std::string& name = setup.name;

  if (sim_->robot(sim_->findModel(name))) {
    throw ModelError("robot '" + name + "' exists already: robot names must be unique");
  }
  RobotBridge::Options bridge;
  bridge.ns = setup.ns;
  for (const auto& other : robots_) {
    if (other->ns() == bridge.ns) {
      throw ModelError("robot '" + name + "' (" + model.source + "): its ros_control namespace " +
                       bridge.ns + " is already robot '" + sim_->robot(other->id())->name +
                       "''s; give each robot its own (e.g. xacro robot_namespace:=/" + name + ")");
    }
  }
  // Frames: tf_prefix from the robot's namespace, as robot_state_publisher finds it.
  std::string key;
  if (ros::NodeHandle(bridge.ns).searchParam("tf_prefix", key)) nh_.getParam(key, bridge.tf_prefix);
  bridge.tf_prefix = trimSlashes(bridge.tf_prefix);
  rp.param<std::string>("odom_frame", bridge.odom_frame, "odom");
  bridge.ground_truth_rate = ground_truth_rate_;
  bridge.control_ns = setup.control_ns;
  bridge.controller_manager = model.ext.ros_control.has_value();
  if (model.ext.ros_control) bridge.e_stop_topic = model.ext.ros_control->e_stop_topic;
  bridge.controllers_changed = [this] { updateCommandTopics(); };

  RobotSpawn spawn;
  spawn.name = name;
  spawn.X_WB = X_WB;
  spawn.drop_to_ground = auto_z;
  spawn.tf_prefix = bridge.tf_prefix;
  spawn.controllers = setup.controllers;
  spawn.hw_sim = readRobotHwSimParams(setup.ns);
  bool given = false;
  spawn.disabled_sensors = getNameList(rp, "disable_sensors", &given);
  if (!given) spawn.disabled_sensors = getNameList(pnh_, "disable_sensors", &given);
  spawn.model = std::move(model);
  // Each sensor gets its publisher; the topics it claims are the robot's.
  auto topics = std::make_shared<std::vector<std::string>>();
  PublisherSetup publisher;
  publisher.robot_name = name;
  publisher.tf_prefix = bridge.tf_prefix;
  publisher.root = root_;
  publisher.static_tf = &staticTf();
  publisher.profile = profile_.get();
  publisher.claim_topic = [this, topics](const std::string& topic, const std::string& owner) {
    claimTopic(topic, owner);
    topics->push_back(topic);
  };
  spawn.attach = [publisher](SimSensor& sensor) {
    sensor.setListener(makeSensorPublisher(sensor, publisher));
  };

  // The robot's topics before its sensors' (as a subscriber of joint_states sees them at start).
  spawn.added = [&](ModelId id) {
    const SimRobot& robot = *sim_->robot(id);
    JointStates joints;
    sim_->jointStates(id, &joints);
    ROS_INFO_STREAM("robot '" << name << "' (" << robot.model.source << "): "
                    << joints.name.size() << " movable joints, " << robot.handles.size()
                    << " transmissions, controllers [" << [&] {
                         std::string s;
                         for (const auto& c : robot.controllers.controllers()) s += " " + c->name();
                         return s + " ]";
                       }()
                    << " in " << bridge.ns << ", spawned at ("
                    << sim_->entities().spawnPose(id).translation().transpose() << ")"
                    << (bridge.tf_prefix.empty() ? "" : ", frames prefixed " + bridge.tf_prefix + "/"));
    robots_.push_back(std::make_unique<RobotBridge>(*sim_, id, bridge, root_, staticTf()));
    contacts_->addRobot(root_, robot.id, name, bridge.ns);
  };
  ModelId id = kNoModel;
  try {
    id = sim_->addRobot(std::move(spawn));
  } catch (...) {
    // Nothing half-spawned: what was set up goes again.
    for (const std::string& topic : *topics) topic_owner_.erase(topic);
    if (!robots_.empty() && !sim_->robot(robots_.back()->id())) {  // its bridge was made
      contacts_->removeRobot(robots_.back()->physicsId());
      robots_.pop_back();
    }
    throw;
  }
  robots_.back()->topics() = *topics;
  updateCommandTopics();
  const SimRobot& robot = *sim_->robot(id);
  // A table that leaves something out is a warning (the user's model does less here than in
  // Gazebo), unless the user left it out with ~disable_sensors.
  const std::vector<ReportRow> report = modelReport(robot.model, name, sim_->leftOut(id));
  if (leavesOutUnasked(report)) {
    ROS_WARN_STREAM(formatModelReport(name, report));
  } else {
    ROS_INFO_STREAM(formatModelReport(name, report));
  }
}

void SimNode::claimTopic(const std::string& topic, const std::string& owner) {
  const auto [it, fresh] = topic_owner_.emplace(topic, owner);
  if (!fresh) {
    throw std::runtime_error(topic + " is already published by " + it->second +
                             "; give each robot's sensors their own namespace (e.g. xacro "
                             "sensor_namespace:=/<robot name>)");
  }
}

void SimNode::attachWorldSensor(SimSensor& sensor) {
  PublisherSetup publisher;
  publisher.robot_name = sensor.modelName();
  publisher.root = root_;
  publisher.static_tf = &staticTf();
  publisher.world_model = true;
  const std::string model = sensor.modelName();
  publisher.profile = profile_.get();
  publisher.claim_topic = [this, model](const std::string& topic, const std::string& owner) {
    claimTopic(topic, owner);
    world_model_topics_[model].push_back(topic);
  };
  sensor.setListener(makeSensorPublisher(sensor, publisher));
}

void SimNode::spawnRobot(const std::string& name, const std::string& urdf,
                         const Eigen::Isometry3d& X_WB) {
  const ros::NodeHandle rp(pnh_, name);
  LoadOptions options = loadOptions(rp);
  options.warn = [](const std::string& w) { warnOnce(w); };
  RobotModel model = loadRobotModel(urdf, "spawn_urdf_model '" + name + "'", options);
  const RobotSetup setup = setUpRobot(model, name, true, rp);
  addRobot(std::move(model), setup, X_WB, false, rp);
}

void SimNode::spawnWorldModel(const std::string& name, const std::string& sdf,
                              const Eigen::Isometry3d& X_WM) {
  ModelDescription model = loadModelString(sdf, "spawn_sdf_model '" + name + "'", "",
                                           world_options_);
  // gazebo_ros: the model's own <pose> is relative to initial_pose.
  model.name = name;
  model.X_WM = X_WM * model.X_WM;
  sim_->addWorldModel(std::move(model));
}

void SimNode::deleteModel(const std::string& name) {
  const ModelId id = sim_->findModel(name);
  const auto it = std::find_if(robots_.begin(), robots_.end(),
                               [id](const auto& r) { return r->id() == id; });
  if (it != robots_.end()) {
    for (const std::string& topic : (*it)->topics()) topic_owner_.erase(topic);
    contacts_->removeRobot((*it)->physicsId());
    // Its command subscribers go before the controllers they point into.
    robots_.erase(it);
    updateCommandTopics();
  }
  sim_->removeModel(name);
  // A world model's sensor topics are free again once its sensors (and publishers) are gone.
  const auto topics = world_model_topics_.find(name);
  if (topics != world_model_topics_.end()) {
    for (const std::string& topic : topics->second) topic_owner_.erase(topic);
    world_model_topics_.erase(topics);
  }
}

}  // namespace tianracer_sim
