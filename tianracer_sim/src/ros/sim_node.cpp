#include "tianracer_sim/ros/sim_node.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

#include <nav_msgs/Odometry.h>
#include <ros/package.h>
#include <rosgraph_msgs/Clock.h>

#include <tianracer_control/frames.h>

#include "tianracer_sim/model/sensor_topics.h"
#include "tianracer_sim/sensors/model_report.h"
#include "tianracer_sim/sensors/sensor_registry.h"
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/TransformStamped.h>

#include "tianracer_sim/sim/world_physics.h"
#include "tianracer_sim/ros/controller_params.h"
#include "tianracer_sim/ros/state_msgs.h"

namespace tianracer_sim {

namespace tc = tianracer_control;

namespace {

std::string trimSlashes(std::string s) {
  while (!s.empty() && s.front() == '/') s.erase(s.begin());
  while (!s.empty() && s.back() == '/') s.pop_back();
  return s;
}

double getDouble(const ros::NodeHandle& pnh, const std::string& key, double fallback) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(key, v)) return fallback;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(v);
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(v);
  throw std::runtime_error("parameter " + pnh.resolveName(key) + " must be a number, got " +
                           v.toXml());
}

std::vector<std::string> getNameList(const ros::NodeHandle& pnh, const std::string& key,
                                     bool* given) {
  std::vector<std::string> names;
  XmlRpc::XmlRpcValue v;
  *given = pnh.getParam(key, v);
  if (!*given) return names;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < v.size(); ++i) {
      if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString) {
        throw std::runtime_error("parameter " + pnh.resolveName(key) + " must list names");
      }
      names.push_back(static_cast<std::string>(v[i]));
    }
  } else if (v.getType() == XmlRpc::XmlRpcValue::TypeString) {
    std::istringstream in(static_cast<std::string>(v));
    for (std::string n; in >> n;) names.push_back(n);
  } else {
    throw std::runtime_error("parameter " + pnh.resolveName(key) +
                             " must be a list or a space-separated string");
  }
  return names;
}

}  // namespace

void SimNode::warnOnce(const std::string& text) {
  static std::set<std::string> seen;
  if (seen.insert(text).second) ROS_WARN_STREAM(text);
}

SimNode::SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh), pnh_(pnh) {
  nh_.setCallbackQueue(&queue_);
  pnh_.setCallbackQueue(&queue_);

  // The world: a shipped name or a .world path. Its <physics> gives the step and gravity.
  std::string world_arg;
  pnh_.param<std::string>("world", world_arg, "empty");
  world_options_.warn = [](const std::string& w) { warnOnce(w); };
  // A model or mesh that cannot be used is an error and the rest loads, as in Gazebo;
  // ~strict_world:=true stops instead (CI).
  world_options_.error = [](const std::string& e) { ROS_ERROR_STREAM(e); };
  pnh_.param("strict_world", world_options_.strict, false);
  world_options_.find_package = [](const std::string& pkg) { return ros::package::getPath(pkg); };
  world_ = std::make_unique<WorldDescription>(loadWorldFile(
      resolveWorld(world_arg, ros::package::getPath("tianracer_sim") + "/worlds"), world_options_));

  PhysicsOptions physics = physicsOptionsFor(*world_);
  physics.dt = getDouble(pnh_, "max_step_size", physics.dt);
  if (!(physics.dt > 0.0 && physics.dt <= 0.1)) {
    throw std::runtime_error("parameter ~max_step_size must be in (0, 0.1] s, got " +
                             std::to_string(physics.dt));
  }
  real_time_factor_ = getDouble(pnh_, "real_time_factor", world_->physics.real_time_factor);
  if (!(real_time_factor_ >= 0.0) || !std::isfinite(real_time_factor_)) {
    throw std::runtime_error("parameter ~real_time_factor must be >= 0 (0 = as fast as possible), got " +
                             std::to_string(real_time_factor_));
  }
  pnh_.param("paused", paused_, false);
  // /clock every 5 ms of sim time by default: running 10x faster than real time, 1 kHz would
  // be 10,000 messages a second to every node, more than a rospy node can read.
  const double clock_rate = getDouble(pnh_, "clock_rate", 200.0);
  clock_schedule_.period = clock_rate > 0.0 ? 1.0 / clock_rate : 0.0;
  ground_truth_rate_ = getDouble(pnh_, "ground_truth_rate", 50.0);
  int seed = 0;
  pnh_.param("seed", seed, 0);
  seed_ = static_cast<std::uint64_t>(seed);
  status_period_ = getDouble(pnh_, "status_period", 5.0);

  sim_ = std::make_unique<Simulation>(physics, [](const std::string& w) { warnOnce(w); });
  int shapes = 0;
  for (const ModelDescription& model : world_->models) {
    const WorldModelBodies added = addModelToPhysics(*world_, model, &sim_->physics(),
                                                     [](const std::string& w) { warnOnce(w); });
    shapes += added.shapes;
    world_bodies_[model.name] = added;
  }
  addToScene(*world_, scene_);
  ROS_INFO("world '%s' (%s): %zu models, %d collision shapes, ground plane %s", world_->name.c_str(),
           world_->source.c_str(), world_->models.size(), shapes, world_->ground_plane ? "yes" : "no");

  // /clock first, so that nodes waiting for sim time see it as soon as we step.
  ros::NodeHandle root;
  root.setCallbackQueue(&queue_);
  nh_.setParam("/use_sim_time", true);
  clock_pub_ = root.advertise<rosgraph_msgs::Clock>("/clock", 10);
  diagnostics_pub_ = root.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10);
  contacts_ = std::make_unique<ContactPublisher>(staticShapeOwners(*world_));

  bool several = false;
  const std::vector<std::string> robot_names = getNameList(pnh_, "robots", &several);
  if (!several) {
    loadRobot(pnh_, "");
  } else if (robot_names.empty()) {
    throw std::runtime_error("parameter " + pnh_.resolveName("robots") +
                             " lists no robot: name the robots to spawn, or leave it unset for "
                             "one robot from the node's own parameters");
  } else {
    for (const std::string& name : robot_names) loadRobot(ros::NodeHandle(pnh_, name), name);
  }

  std::vector<std::string> command_topics;
  for (const RobotIo& io : robots_) {
    for (const std::string& t : io.commands->topics()) command_topics.push_back(t);
  }
  LockstepOptions lockstep = lockstepOptions(pnh_, command_topics);
  if (lockstep.enabled()) {
    lockstep_ = std::make_unique<Lockstep>(root, &queue_, lockstep);
    ROS_INFO("lockstep: each %g s waits for %zu reply topics, each %g s for %zu tick topics "
             "(timeout %g s wall)", lockstep.reply_period, lockstep.replies.size(),
             lockstep.tick_period, lockstep.ticks.size(), lockstep.timeout);
  }

  ros::NodeHandle gazebo("/gazebo");
  gazebo.setCallbackQueue(&queue_);
  services_.push_back(gazebo.advertiseService("pause_physics", &SimNode::onPause, this));
  services_.push_back(gazebo.advertiseService("unpause_physics", &SimNode::onUnpause, this));
  services_.push_back(gazebo.advertiseService("reset_simulation", &SimNode::onResetSimulation, this));
  services_.push_back(gazebo.advertiseService("reset_world", &SimNode::onResetWorld, this));
  GazeboInterface::Options gazebo_options;
  gazebo_options.states_rate = getDouble(pnh_, "gazebo_states_rate", gazebo_options.states_rate);
  gazebo_ = std::make_unique<GazeboInterface>(gazebo, *sim_, *world_, gazebo_options,
                                             static_cast<ModelSpawner*>(this));

  ROS_INFO("tianracer_sim: step %.4f s, real_time_factor %g%s, %s", physics.dt, real_time_factor_,
           real_time_factor_ == 0.0 ? " (as fast as possible)" : "", paused_ ? "paused" : "running");
}

SimNode::~SimNode() {
  camera_worker_.reset();  // finish the frame in flight while its sensors still exist
}

void SimNode::loadRobot(const ros::NodeHandle& rp, const std::string& fixed_name) {
  LoadOptions options;
  options.resolver.find_package = [](const std::string& pkg) { return ros::package::getPath(pkg); };
  options.warn = [](const std::string& w) { warnOnce(w); };

  std::string model_file;
  rp.param<std::string>("model", model_file, "");
  // Relative mesh URIs of a robot_description filled from a file resolve against its folder.
  rp.param<std::string>("model_dir", options.resolver.base_dir, "");
  RobotModel model;
  if (!model_file.empty()) {
    model = loadRobotModelFile(model_file, options);
  } else {
    std::string param;
    rp.param<std::string>("robot_param", param, "robot_description");
    std::string urdf;
    if (!nh_.getParam(param, urdf)) {
      throw ModelError("parameter " + nh_.resolveName(param) +
                       " is not set: load the URDF (e.g. with xacro) or give ~model");
    }
    if (urdf.find_first_not_of(" \t\r\n") == std::string::npos) {
      throw ModelError("parameter " + nh_.resolveName(param) + " (robot_description) is empty");
    }
    model = loadRobotModel(urdf, nh_.resolveName(param), options);
  }

  RobotRequest request;
  std::string name = fixed_name;
  const std::string model_ns =
      trimSlashes(model.ext.ros_control ? model.ext.ros_control->robot_namespace : "");
  if (name.empty()) {
    rp.param<std::string>("robot_name", name, model_ns);
    if (!model_ns.empty() && name != model_ns) {
      // robot_state_publisher and the control nodes of the launch files follow robot_name.
      ROS_WARN_STREAM("robot '" << name << "': ~robot_name is '" << name << "' but the model's "
                      << "gazebo_ros_control robotNamespace is '/" << model_ns << "': its "
                      << "controllers and joint_states are under /" << model_ns << ", not /"
                      << name << " (give the model its namespace, e.g. model_args:=\"robot_namespace:=/"
                      << name << "\", or robot_name:=" << model_ns << ")");
    }
  }
  if (name.empty()) name = model.urdf->getName();

  // Spawn pose.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  const double roll = getDouble(rp, "roll", 0.0), pitch = getDouble(rp, "pitch", 0.0),
               yaw = getDouble(rp, "yaw", 0.0);
  X_WB.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                      .toRotationMatrix();
  X_WB.translation() = Eigen::Vector3d(getDouble(rp, "x", 0.0), getDouble(rp, "y", 0.0), 0.0);
  bool auto_z = true;
  XmlRpc::XmlRpcValue zv;
  if (rp.getParam("z", zv) && !(zv.getType() == XmlRpc::XmlRpcValue::TypeString &&
                                  static_cast<std::string>(zv) == "auto")) {
    X_WB.translation().z() = getDouble(rp, "z", 0.0);
    auto_z = false;
  }
  if (const std::string bad = checkModelState(X_WB, Twist()); !bad.empty())
    throw std::runtime_error("spawn pose (~x ~y ~z ~roll ~pitch ~yaw): " + bad);

  request.model = std::move(model);
  request.name = name;
  request.X_WB = X_WB;
  request.auto_z = auto_z;
  request.rp = rp;
  addRobot(std::move(request));
}

void SimNode::addRobot(RobotRequest request) {
  const ros::NodeHandle& rp = request.rp;
  const std::string& name = request.name;
  RobotModel& model = request.model;
  for (const RobotIo& other : robots_) {
    if (other.robot && other.robot->name == name) {
      throw ModelError("robot '" + name + "' exists already: robot names must be unique");
    }
  }
  RobotIo io;
  io.ns = model.ext.ros_control ? model.ext.ros_control->robot_namespace : "";
  if (io.ns.empty()) io.ns = "/" + name;
  io.ns = "/" + trimSlashes(io.ns);
  for (const RobotIo& other : robots_) {
    if (other.robot && other.ns == io.ns) {
      throw ModelError("robot '" + name + "' (" + model.source + "): its ros_control namespace " +
                       io.ns + " is already robot '" + other.robot->name +
                       "''s; give each robot its own (e.g. xacro robot_namespace:=/" + name + ")");
    }
  }

  // Controllers: the list given, else every controller defined under the namespace.
  std::string control_ns;
  rp.param<std::string>("control_namespace", control_ns, io.ns);
  ros::NodeHandle control_nh(control_ns);
  bool given = false;
  std::vector<std::string> names = getNameList(rp, "controllers", &given);
  if (!given) names = listControllers(control_nh);
  RobotConfig config;
  config.name = name;
  config.X_WB_spawn = request.X_WB;
  config.drop_to_ground = request.auto_z;
  config.controllers = tc::loadControllerSpecs(control_nh, names);
  config.model = std::move(model);

  // Frames: tf_prefix from the robot's namespace, as robot_state_publisher finds it.
  std::string key;
  if (ros::NodeHandle(io.ns).searchParam("tf_prefix", key)) nh_.getParam(key, io.tf_prefix);
  io.tf_prefix = trimSlashes(io.tf_prefix);

  SimRobot& robot = sim_->addRobot(std::move(config));
  io.robot = &robot;
  robots_.push_back(std::move(io));
  const std::size_t index = robots_.size() - 1;
  try {
    setUpRobotIo(index, rp);
  } catch (...) {
    // Nothing half-spawned: what was set up goes again.
    removeRobotAt(index);
    robots_.pop_back();
    throw;
  }
}

void SimNode::setUpRobotIo(std::size_t index, const ros::NodeHandle& rp) {
  RobotIo& io = robots_[index];
  SimRobot& robot = *io.robot;
  const std::string& name = robot.name;
  io.scene_bodies = addRobotToScene(robot.model, robot.name, &scene_);
  PhysicsRobot& pr = sim_->physics().robot(robot.id);
  ROS_INFO_STREAM("robot '" << name << "' (" << robot.model.source << "): "
                  << pr.joints().size() << " movable joints, " << robot.handles.size()
                  << " transmissions, controllers [" << [&] {
                       std::string s;
                       for (const auto& c : robot.controllers.controllers()) s += " " + c->name();
                       return s + " ]";
                     }()
                  << " in " << io.ns << ", spawned at (" << pr.spawnPose().translation().transpose()
                  << ")" << (io.tf_prefix.empty() ? "" : ", frames prefixed " + io.tf_prefix + "/"));
  io.base_frame = tc::resolveFrame(io.tf_prefix, pr.tree().bodies.front().link);

  // world -> odom at the spawn pose: wheel odometry starts there, so rviz can show the
  // ground truth (world) and the odometry (odom) together.
  std::string odom_frame;
  rp.param<std::string>("odom_frame", odom_frame, "odom");
  if (!odom_frame.empty()) {
    geometry_msgs::TransformStamped tf;
    tf.header.frame_id = "world";
    tf.child_frame_id = tc::resolveFrame(io.tf_prefix, odom_frame);
    const geometry_msgs::Pose p = toPose(pr.spawnPose());
    tf.transform.translation.x = p.position.x;
    tf.transform.translation.y = p.position.y;
    tf.transform.translation.z = p.position.z;
    tf.transform.rotation = p.orientation;
    static_tf_.sendTransform(tf);
  }

  setUpJointStates(io);
  ros::NodeHandle robot_nh(io.ns);
  robot_nh.setCallbackQueue(&queue_);
  io.commands = std::make_shared<tc::ControllerCommandSubscribers>(robot_nh, robot.controllers);
  io.ground_truth = robot_nh.advertise<nav_msgs::Odometry>("ground_truth/odom", 10);
  io.ground_truth_schedule.period = ground_truth_rate_ > 0.0 ? 1.0 / ground_truth_rate_ : 0.0;
  ros::NodeHandle root;
  root.setCallbackQueue(&queue_);
  contacts_->addRobot(root, robot.id, robot.name, io.ns);
  setUpSensors(index, rp);
  // A table that leaves something out is a warning (the user's model does less here than in
  // Gazebo), unless the user left it out with ~disable_sensors.
  const std::vector<ReportRow> report = modelReport(robot.model, name, left_out_);
  if (leavesOutUnasked(report)) {
    ROS_WARN_STREAM(formatModelReport(name, report));
  } else {
    ROS_INFO_STREAM(formatModelReport(name, report));
  }
  left_out_.clear();
}

void SimNode::setUpSensors(size_t robot_index, const ros::NodeHandle& rp) {
  RobotIo& io = robots_[robot_index];
  bool given = false;
  std::vector<std::string> disabled = getNameList(rp, "disable_sensors", &given);
  if (!given) disabled = getNameList(pnh_, "disable_sensors", &given);
  for (const auto& [link, ext] : io.robot->model.ext.links) {
    for (const SensorSpec& spec : ext.sensors) {
      if (std::find(disabled.begin(), disabled.end(), spec.type) != disabled.end() ||
          std::find(disabled.begin(), disabled.end(), spec.name) != disabled.end()) {
        ROS_INFO("sensor '%s' (%s) on link %s disabled by ~disable_sensors", spec.name.c_str(),
                 spec.type.c_str(), link.c_str());
        left_out_[spec.name] = kDisabledBySensorList;
        continue;
      }
      setUpSensor(robot_index, spec);
    }
  }
  // Model plugins that publish like sensors (an IMU plugin, ground truth) go the same way.
  for (const PluginSpec& plugin : io.robot->model.ext.model_plugins) {
    const SensorSpec spec = modelPluginSensor(plugin);
    if (!findSensorKind(spec)) continue;
    if (std::find(disabled.begin(), disabled.end(), spec.name) != disabled.end()) {
      ROS_INFO("plugin '%s' (%s) disabled by ~disable_sensors", spec.name.c_str(),
               plugin.filename.c_str());
      left_out_[spec.name] = kDisabledBySensorList;
      continue;
    }
    setUpSensor(robot_index, spec);
  }
}

void SimNode::setUpSensor(size_t robot_index, const SensorSpec& spec) {
  RobotIo& io = robots_[robot_index];
  const PhysicsRobot& pr = sim_->physics().robot(io.robot->id);
  const std::string what = spec.type.empty() ? "plugin" : "sensor";
  if (!spec.error.empty()) {
    ROS_ERROR("robot '%s': %s '%s' left out: %s", io.robot->name.c_str(), what.c_str(),
              spec.name.c_str(), spec.error.c_str());
    return;
  }
  const SensorKind* kind = findSensorKind(spec);
  if (!kind) {
    warnOnce("robot '" + io.robot->name + "': sensor '" + spec.name + "' of type '" + spec.type +
             "' is not supported; left out");
    return;
  }
  ros::NodeHandle root;
  root.setCallbackQueue(&queue_);
  SensorSetup setup;
  setup.spec = &spec;
  setup.robot = robot_index;
  setup.robot_name = io.robot->name;
  setup.tf_prefix = io.tf_prefix;
  for (const auto& [body, body_link] : io.scene_bodies.links) {
    if (body_link == spec.link) setup.own_body = body;
  }
  setup.seed = seed_;
  setup.index = sensors_of_kind_[kind->id];
  setup.gravity = sim_->physics().options().gravity;
  setup.dt = sim_->physics().options().dt;
  setup.root = root;
  setup.static_tf = &static_tf_;
  setup.warn = [](const std::string& w) { warnOnce(w); };
  setup.check_link = [&pr](const std::string& l) { (void)pr.linkPose(l); };
  setup.claim_topic = [this, robot_index](const std::string& topic, const std::string& owner) {
    claimTopic(topic, owner);
    robots_[robot_index].topics.push_back(topic);
  };
  setup.renderer = [this]() { return ensureRenderer() ? renderer_.get() : nullptr; };
  setup.add_stat = [this, robot_index](const std::string& name, double target) {
    stats_.push_back({name, target, 0, 0});
    robots_[robot_index].stats.push_back(stats_.size() - 1);
    return stats_.size() - 1;
  };
  // A bad sensor is reported and left out; the robot and the other sensors run on.
  try {
    std::unique_ptr<SensorPublisher> sensor = makeSensorPublisher(*kind, setup);
    if (!sensor) return;
    sensors_.push_back(std::move(sensor));
    sensor_robot_.push_back(robot_index);
    ++sensors_of_kind_[kind->id];
  } catch (const std::exception& e) {
    ROS_ERROR("robot '%s': %s '%s' on link '%s' left out: %s", io.robot->name.c_str(),
              what.c_str(), spec.name.c_str(), spec.link.c_str(), e.what());
    left_out_[spec.name] = e.what();
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

bool SimNode::ensureRenderer() {
  if (renderer_) return true;
  if (renderer_failed_) return false;
  try {
    renderer_ = std::make_unique<Renderer>([](const std::string& w) { warnOnce(w); });
    ROS_INFO("cameras render offscreen with %s", renderer_->glInfo().c_str());
    return true;
  } catch (const std::exception& e) {
    renderer_failed_ = true;
    ROS_ERROR("no offscreen rendering (%s): the simulation runs on without cameras", e.what());
    return false;
  }
}

void SimNode::submitFrames(const ros::Time& stamp) {
  // What is due and wanted was decided at the step; the frames are rendered and published on
  // the frame worker from a snapshot of this step's scene (frame_worker.h).
  if (due_frames_.frames.empty()) return;
  updateScene();
  if (!camera_worker_) {
    camera_worker_ = std::make_unique<FrameWorker<FrameJob>>([this](FrameJob& job) {
      try {
        for (const FrameRequest& f : job.frames) f.sensor->renderFrame(render_scene_, f, job.stamp);
      } catch (const std::exception& e) {
        ROS_ERROR_STREAM_THROTTLE(10.0, "camera frame not published: " << e.what());
      }
    });
  }
  camera_worker_->submit([&](FrameJob& job) {
    job.stamp = stamp;
    job.frames.clear();
    std::swap(job.frames, due_frames_.frames);
    snapshotScene(scene_, &render_scene_);
  });
}

const Scene& SimNode::scene() {
  updateScene();
  return scene_;
}

Eigen::Isometry3d SimNode::linkPose(std::size_t robot, const std::string& link) const {
  return sim_->physics().robot(robots_[robot].robot->id).linkPose(link);
}

void SimNode::linkContacts(std::size_t robot, const std::string& link,
                           std::vector<BumperContact>* out) {
  out->clear();
  PhysicsWorld& world = sim_->physics();
  const RobotId id = robots_[robot].robot->id;
  const PhysicsRobot& pr = world.robot(id);
  const auto it = pr.tree().links.find(link);
  if (it == pr.tree().links.end()) return;
  robotContacts(world, id, &contact_scratch_);
  for (const RobotContact& c : contact_scratch_) {
    if (c.body != it->second.first) continue;
    BumperContact b;
    b.own = pr.name() + "::" + pr.tree().bodies.at(c.body).link;
    std::string other_link;
    contacts_->otherOf(world, c, &b.other, &other_link);
    if (!other_link.empty()) b.other += "::" + other_link;
    b.position_W = c.position_W;
    b.normal_W = c.normal_W;
    b.depth = c.depth;
    b.impulse = c.impulse;
    out->push_back(std::move(b));
  }
}

bool SimNode::linkState(std::size_t robot, const std::string& link, LinkState* state) const {
  const PhysicsRobot& pr = sim_->physics().robot(robots_[robot].robot->id);
  const auto it = pr.tree().links.find(link);
  if (it == pr.tree().links.end() || it->second.first != 0) return false;
  const Twist base = pr.baseTwist();
  state->X_WL = pr.linkPose(link);
  state->w_W = base.angular;
  state->v_W = base.linear + base.angular.cross(state->X_WL.translation() -
                                                pr.basePose().translation());
  return true;
}

void SimNode::updateScene() {
  if (scene_step_ == sim_->stepCount()) return;
  for (const RobotIo& io : robots_) {
    if (!io.robot) continue;
    updateRobotScene(sim_->physics().robot(io.robot->id), io.scene_bodies, &scene_);
  }
  updateFreeBodyScene(sim_->physics(), &scene_);
  scene_step_ = sim_->stepCount();
}

void SimNode::setUpJointStates(RobotIo& io) {
  // Both the joint_state_publisher plugin and joint_state_controller publish JointState; when
  // they resolve to the same topic they become ONE stream (one publisher): the plugin's joints
  // in its order, then the controller's other joints, at the higher of the two rates.
  struct Request {
    std::string topic;
    std::vector<std::string> joints;
    double rate;
    std::string source;
  };
  std::vector<Request> requests;
  const RobotModel& model = io.robot->model;
  const PhysicsRobot& pr = sim_->physics().robot(io.robot->id);
  if (const auto& jsp = model.ext.joint_state_publisher) {
    requests.push_back({resolveTopic(jsp->robot_namespace, "joint_states"), jsp->joint_names,
                        jsp->update_rate, "joint_state_publisher plugin"});
  }
  for (const auto& c : io.robot->controllers.controllers()) {
    if (auto* jsc = dynamic_cast<const tc::JointStateController*>(c.get())) {
      std::vector<std::string> joints;
      for (const auto& h : io.robot->handles) joints.push_back(h.name);
      requests.push_back({resolveTopic(io.ns, "joint_states"), joints, jsc->publishRate(),
                          "joint_state_controller '" + c->name() + "'"});
    }
  }
  ros::NodeHandle root;
  root.setCallbackQueue(&queue_);
  for (const Request& r : requests) {
    auto it = std::find_if(io.joint_states.begin(), io.joint_states.end(),
                           [&](const JointStateStream& s) { return s.pub.getTopic() == r.topic; });
    if (it == io.joint_states.end()) {
      JointStateStream s;
      s.pub = root.advertise<sensor_msgs::JointState>(r.topic, 10);
      s.schedule.period = 1.0 / r.rate;
      io.joint_states.push_back(std::move(s));
      it = std::prev(io.joint_states.end());
    } else {
      ROS_INFO_STREAM(r.topic << ": " << r.source
                              << " shares the topic with another joint state source: merged "
                                 "into one stream at the higher rate");
      it->schedule.period = std::min(it->schedule.period, 1.0 / r.rate);
    }
    for (const std::string& j : r.joints) {
      const int idx = pr.jointIndex(j);
      if (idx < 0) throw ModelError(r.source + ": joint '" + j + "' is not a movable joint");
      if (std::find(it->joints.begin(), it->joints.end(), idx) == it->joints.end()) {
        it->joints.push_back(idx);
        it->msg.name.push_back(j);
      }
    }
  }
  for (JointStateStream& s : io.joint_states) {
    s.msg.position.resize(s.joints.size());
    s.msg.velocity.resize(s.joints.size());
    s.msg.effort.resize(s.joints.size());
    ROS_INFO_STREAM(s.pub.getTopic() << ": " << s.joints.size() << " joints at "
                                     << 1.0 / s.schedule.period << " Hz");
  }
}

void SimNode::publishClock() {
  rosgraph_msgs::Clock clock;
  clock.clock = ros::Time(sim_->time());
  clock_pub_.publish(clock);
}

void SimNode::publishDue(bool clock) {
  const double t = sim_->time();
  const ros::Time stamp(t);
  if (clock_schedule_.due(t) && clock) publishClock();
  for (RobotIo& io : robots_) {
    if (!io.robot) continue;
    const PhysicsRobot& pr = sim_->physics().robot(io.robot->id);
    for (JointStateStream& s : io.joint_states) {
      if (!s.schedule.due(t) || s.pub.getNumSubscribers() == 0) continue;
      s.msg.header.stamp = stamp;
      for (size_t k = 0; k < s.joints.size(); ++k) {
        s.msg.position[k] = pr.jointPosition(s.joints[k]);
        s.msg.velocity[k] = pr.jointVelocity(s.joints[k]);
        s.msg.effort[k] = pr.jointEffort(s.joints[k]);
      }
      s.pub.publish(s.msg);
    }
    if (io.ground_truth_schedule.due(t) && io.ground_truth.getNumSubscribers() > 0) {
      io.ground_truth.publish(
          toGroundTruth(pr.basePose(), pr.baseTwist(), stamp, "world", io.base_frame));
    }
  }
  for (const auto& sensor : sensors_) sensor->step(t, stamp, *this);
  submitFrames(stamp);
}

void SimNode::restartSchedules() {
  const double t = sim_->time();
  clock_schedule_.restart(t);
  for (const auto& sensor : sensors_) sensor->restart(t);
  for (RobotIo& io : robots_) {
    for (JointStateStream& s : io.joint_states) s.schedule.restart(t);
    io.ground_truth_schedule.restart(t);
  }
}

void SimNode::stepOnce() {
  for (RobotIo& io : robots_)
    if (io.commands) io.commands->apply();
  gazebo_->beforeStep();
  sim_->step();
  contacts_->update(sim_->physics(), sim_->time());
  const double t = sim_->time();
  const bool replies = lockstep_ && lockstep_->repliesDue(t);
  const bool ticks = lockstep_ && lockstep_->ticksDue(t);
  if (!replies && !ticks) {
    publishDue();
  } else {
    // The driver answers this step's sensor data before the clock moves on to this step, so
    // that nodes on sim-time timers (the cmd_vel node) tick with its answer in hand.
    if (replies) lockstep_->markReplies();
    publishDue(false);
    if (replies) lockstep_->awaitReplies(t);
    if (ticks) lockstep_->markTicks();
    publishClock();
    if (ticks) lockstep_->awaitTicks(t);
  }
  gazebo_->afterStep();
}

void SimNode::run() {
  publishClock();
  publishDue();
  status_wall_ = ros::WallTime::now();
  status_sim_ = sim_->time();
  ros::WallTime wall0 = ros::WallTime::now();
  double sim0 = sim_->time();
  while (ros::ok()) {
    queue_.callAvailable(ros::WallDuration(0.0));
    if (paused_) {
      queue_.callAvailable(ros::WallDuration(0.01));
      publishStatus();
      pacing_reset_ = true;
      continue;
    }
    if (pacing_reset_) {
      wall0 = ros::WallTime::now();
      sim0 = sim_->time();
      pacing_reset_ = false;
    }
    stepOnce();
    if ((sim_->stepCount() & 255) == 0) publishStatus();
    if (real_time_factor_ > 0.0) {
      const ros::WallTime target = wall0 + ros::WallDuration((sim_->time() - sim0) / real_time_factor_);
      const ros::WallTime now = ros::WallTime::now();
      if (now < target) {
        // Wait for wall time, serving commands and services meanwhile.
        queue_.callAvailable(target - now);
        const ros::WallTime after = ros::WallTime::now();
        if (after < target) (target - after).sleep();
      } else if ((now - target).toSec() > 0.5) {
        pacing_reset_ = true;  // far behind: do not race to catch up
      }
    }
  }
}

bool SimNode::onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = true;
  return true;
}

bool SimNode::onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  paused_ = false;
  return true;
}

bool SimNode::onResetSimulation(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  if (camera_worker_) camera_worker_->wait();  // the frame in flight goes out before time jumps back
  for (RobotIo& io : robots_)
    if (io.commands) io.commands->clear();
  sim_->resetSimulation();
  gazebo_->onReset();
  contacts_->reset();
  restartSchedules();
  if (lockstep_) lockstep_->restart(sim_->time());
  pacing_reset_ = true;
  publishClock();
  return true;
}

bool SimNode::onResetWorld(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  sim_->resetWorld();
  gazebo_->onReset();
  contacts_->reset();
  return true;
}

}  // namespace tianracer_sim
