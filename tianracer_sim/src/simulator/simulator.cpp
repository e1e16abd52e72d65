#include "tianracer_sim/simulator/simulator.h"

#include <algorithm>
#include <stdexcept>

#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

PhysicsOptions physicsFor(const WorldDescription& world, double max_step_size) {
  PhysicsOptions physics = physicsOptionsFor(world);
  if (max_step_size != 0.0) physics.dt = max_step_size;
  if (!(physics.dt > 0.0 && physics.dt <= 0.1)) {
    throw std::invalid_argument("max_step_size must be in (0, 0.1] s, got " +
                                std::to_string(physics.dt));
  }
  return physics;
}


}  // namespace

Simulator::Simulator(WorldDescription world, SimulatorOptions options)
    : options_(std::move(options)),
      world_(std::make_unique<WorldDescription>(std::move(world))),
      sim_(physicsFor(*world_, options_.max_step_size), options_.log.warn),
      contacts_(staticShapeOwners(*world_)) {
  step_row_ = profileRow(options_.profile, StepProfile::kStep);
  sim_.setProfile(options_.profile);
  contacts_row_ = profileRow(options_.profile, StepProfile::kContactScan);
  scene_row_ = profileRow(options_.profile, "sensors: sample / scene: bodies to this step's poses");
  caster_.setProfile(options_.profile);
  sensors_ = std::make_unique<SensorHost>(*this, scene_, [this]() { updateScene(); }, options_.log,
                                          options_.profile);
  int shapes = 0;
  for (const ModelDescription& m : world_->models) {
    Model entry;
    entry.name = m.name;
    entry.bodies = addModelToPhysics(*world_, m, &sim_.physics(), options_.log.warn);
    shapes += entry.bodies.shapes;
    models_.push_back(std::move(entry));
  }
  for (std::size_t i = 0; i < world_->actors.size(); ++i) {
    Model entry;
    entry.name = world_->actors[i].model.name;
    entry.actor = static_cast<int>(i);
    // Gazebo's actors are static models (sdf/1.6/actor.sdf: <static> defaults to true; Model::
    // Load) whose links Actor::Update moves: their collisions are static shapes moved each step.
    const ModelDescription& a = world_->actors[i].model;
    for (const LinkDescription& l : a.links) {
      for (const CollisionDescription& c : l.collisions) {
        ActorShape as;
        as.actor = static_cast<int>(i);
        as.X_AS = l.X_ML * c.X_LS;
        as.shape = sim_.physics().addStaticShape(staticShapeOf(a, l, c));
        entry.bodies.statics.push_back(as.shape);
        actor_shapes_.push_back(as);
        ++shapes;
      }
    }
    models_.push_back(std::move(entry));
  }
  actor_players_ = actorPlayers(*world_, sim_.dt());
  actor_physics_players_ = actor_players_;
  addToScene(*world_, scene_);
  // The run loop's pace: Gazebo's real-time factor is real_time_update_rate * max_step_size.
  properties_ = std::make_unique<Properties>(*this, sim_, scene_, [this]() { scene_step_ = ~0ull; },
                                             world_->physics.real_time_factor / sim_.dt());
  for (std::size_t id = 0; id < models_.size(); ++id) setUpWorldModelSensors(static_cast<ModelId>(id));
  char line[512];
  std::snprintf(line, sizeof(line), "world '%s' (%s): %zu models, %d collision shapes, ground plane %s",
                world_->name.c_str(), world_->source.c_str(), world_->models.size(), shapes,
                world_->ground_plane ? "yes" : "no");
  say(options_.log.info, line);
}

Simulator::~Simulator() {
  sensors_.reset();  // the frame in flight finishes while the scene and the physics exist
}

// --- models ---------------------------------------------------------------------------------------

ModelId Simulator::addRobot(RobotSpawn spawn) {
  // Its cameras are set up on the renderer the frame worker may be drawing with.
  waitFrames();
  RobotConfig config;
  config.name = spawn.name;
  config.X_WB_spawn = spawn.X_WB;
  config.drop_to_ground = spawn.drop_to_ground;
  config.controllers = spawn.controllers;
  config.hw_sim = spawn.hw_sim;
  config.model = std::move(spawn.model);
  SimRobot& robot = sim_.addRobot(std::move(config));
  const ModelId id = static_cast<ModelId>(models_.size());
  Model entry;
  entry.name = robot.name;
  entry.robot = &robot;
  models_.push_back(std::move(entry));
  ++models_version_;
  try {
    models_[id].scene_bodies = addRobotToScene(robot.model, robot.name, &scene_);
    scene_step_ = ~0ull;
    contacts_.addRobot(robot.id);
    if (spawn.added) spawn.added(id);
    setUpSensors(id, spawn);
  } catch (...) {
    removeModel(robot.name);  // nothing half-spawned stays
    throw;
  }
  return id;
}

ModelId Simulator::addWorldModel(ModelDescription model) {
  // Its cameras are set up on the renderer the frame worker may be drawing with.
  waitFrames();
  Model entry;
  entry.name = model.name;
  entry.bodies = addModelToPhysics(*world_, model, &sim_.physics(), options_.log.warn);
  // Static shapes were added link by link, collision by collision.
  std::size_t k = 0;
  for (const LinkDescription& link : model.links) {
    for (std::size_t c = 0; c < link.collisions.size() && k < entry.bodies.statics.size(); ++c) {
      contacts_.setStaticOwner(entry.bodies.statics[k++], model.name, link.name);
    }
  }
  WorldDescription one;
  one.models.push_back(model);
  addToScene(one, scene_);
  scene_step_ = ~0ull;
  world_->models.push_back(std::move(model));
  models_.push_back(std::move(entry));
  ++models_version_;
  const ModelId id = static_cast<ModelId>(models_.size() - 1);
  setUpWorldModelSensors(id);
  return id;
}

void Simulator::attachWorldSensors(std::function<void(SimSensor&)> attach) {
  world_attach_ = std::move(attach);
  if (!world_attach_) return;
  for (std::size_t i = 0; i < models_.size(); ++i) {
    Model& m = models_[i];
    if (m.robot || m.name.empty()) continue;
    for (auto& [name, why] :
         sensors_->attachModel(static_cast<ModelId>(i), "model '" + m.name + "'", world_attach_)) {
      m.left_out[name] = why;
    }
  }
}

void Simulator::removeModel(const std::string& name) {
  const ModelId id = findModel(name);
  if (id == kNoModel) {
    throw std::runtime_error("model '" + name + "' cannot be deleted (the ground plane stays)");
  }
  sensors_->removeModel(id);  // after the frame in flight, which may be one of its cameras'
  Model& m = models_[id];
  removeModelFromScene(name, &scene_);
  scene_step_ = ~0ull;
  if (m.robot) {
    contacts_.removeRobot(m.robot->id);
    sim_.removeRobot(name);
  } else if (m.actor >= 0) {
    removeModelFromPhysics(m.bodies, &sim_.physics());
    for (ActorShape& s : actor_shapes_) {
      if (s.actor == m.actor) s.shape = -1;
    }
  } else {
    removeModelFromPhysics(m.bodies, &sim_.physics());
    world_->models.erase(std::find_if(world_->models.begin(), world_->models.end(),
                                      [&](const ModelDescription& d) { return d.name == name; }));
  }
  m = Model();
  ++models_version_;
}

ModelId Simulator::findModel(const std::string& name) const {
  if (name.empty()) return kNoModel;
  for (std::size_t i = 0; i < models_.size(); ++i) {
    if (models_[i].name == name) return static_cast<ModelId>(i);
  }
  return kNoModel;
}

const Simulator::Model* Simulator::model(ModelId id) const {
  if (id < 0 || id >= static_cast<ModelId>(models_.size()) || models_[id].name.empty()) return nullptr;
  return &models_[id];
}

SimRobot* Simulator::robot(ModelId id) {
  const Model* m = model(id);
  return m ? m->robot : nullptr;
}

const SimRobot* Simulator::robot(ModelId id) const {
  const Model* m = model(id);
  return m ? m->robot : nullptr;
}

std::vector<ModelId> Simulator::modelIds() const {
  std::vector<ModelId> ids;
  for (std::size_t i = 0; i < models_.size(); ++i) {
    if (!models_[i].name.empty()) ids.push_back(static_cast<ModelId>(i));
  }
  return ids;
}

const std::string& Simulator::modelName(ModelId id) const {
  static const std::string none;
  const Model* m = model(id);
  return m ? m->name : none;
}

std::vector<ModelId> Simulator::robotIds() const {
  std::vector<ModelId> ids;
  for (std::size_t i = 0; i < models_.size(); ++i) {
    if (models_[i].robot) ids.push_back(static_cast<ModelId>(i));
  }
  return ids;
}

const LeftOut& Simulator::leftOut(ModelId id) const {
  static const LeftOut none;
  const Model* m = model(id);
  return m ? m->left_out : none;
}

const PhysicsRobot* Simulator::physicsOf(ModelId id) const {
  const Model* m = model(id);
  if (!m) throw std::out_of_range("no model with id " + std::to_string(id));
  if (m->robot) return &sim_.physics().robot(m->robot->id);
  const int free = sim_.physics().freeBodyIndex(m->name);
  return free >= 0 ? &sim_.physics().freeBody(free) : nullptr;
}

PhysicsRobot* Simulator::physicsOf(ModelId id) {
  return const_cast<PhysicsRobot*>(static_cast<const Simulator*>(this)->physicsOf(id));
}

// --- sensors --------------------------------------------------------------------------------------

void Simulator::setUpSensors(ModelId id, const RobotSpawn& spawn) {
  const SimRobot& robot = *models_[id].robot;
  const std::vector<std::string>& disabled = spawn.disabled_sensors;
  auto off = [&](const std::string& what) {
    return std::find(disabled.begin(), disabled.end(), what) != disabled.end();
  };
  for (const auto& [link, ext] : robot.model.ext.links) {
    for (const SensorSpec& spec : ext.sensors) {
      if (off(spec.type) || off(spec.name)) {
        say(options_.log.info, "sensor '" + spec.name + "' (" + spec.type + ") on link " + link +
                                   " disabled by ~disable_sensors");
        models_[id].left_out[spec.name] = kDisabledBySensorList;
        continue;
      }
      setUpSensor(id, spec, spawn.tf_prefix, spawn.attach);
    }
  }
  // Model plugins that publish like sensors (an IMU plugin, ground truth) go the same way.
  for (const PluginSpec& plugin : robot.model.ext.model_plugins) {
    const SensorSpec spec = modelPluginSensor(plugin);
    if (!findSensorKind(spec)) continue;
    if (off(spec.name)) {
      say(options_.log.info, "plugin '" + spec.name + "' (" + plugin.filename +
                                 ") disabled by ~disable_sensors");
      models_[id].left_out[spec.name] = kDisabledBySensorList;
      continue;
    }
    setUpSensor(id, spec, spawn.tf_prefix, spawn.attach);
  }
}

void Simulator::setUpWorldModelSensors(ModelId id) {
  // A world model's sensors are made as a robot's are: Gazebo's sensors::SensorManager creates
  // every <sensor> of every link, whatever the model (gazebo/sensors/SensorManager.cc), and
  // their gazebo_ros plugins publish under their own robotNamespace ("" = "/": a world model
  // has no namespace of its own; gazebo_plugins/src/gazebo_ros_camera_utils.cpp,
  // gazebo_ros_laser.cpp).
  const std::string& name = models_[id].name;
  for (const ModelDescription& d : world_->models) {
    if (d.name != name) continue;
    for (const LinkDescription& link : d.links) {
      for (const SensorSpec& spec : link.sensors) {
        setUpSensor(id, spec, "", world_attach_);
      }
    }
    // Model plugins that publish like sensors (ground truth, an IMU plugin), as for a robot.
    for (const PluginSpec& plugin : d.plugins) {
      const SensorSpec spec = modelPluginSensor(plugin);
      if (!findSensorKind(spec)) {
        const std::string why = leftOutPluginReason(plugin.filename);
        say(options_.log.warn, plugin.source + ":" + std::to_string(plugin.line) + ": model '" +
                                   name + "': plugin '" + plugin.name + "' (" + plugin.filename +
                                   ") is not simulated; ignored" + (why.empty() ? "" : ": " + why));
        continue;
      }
      setUpSensor(id, spec, "", world_attach_);
    }
  }
}

void Simulator::setUpSensor(ModelId id, const SensorSpec& spec, const std::string& tf_prefix,
                            const std::function<void(SimSensor&)>& attach) {
  Model& m = models_[id];
  SimSensorSetup setup;
  setup.spec = &spec;
  setup.model = id;
  setup.model_name = m.name;
  setup.tf_prefix = tf_prefix;
  if (m.robot) {
    const PhysicsRobot& pr = sim_.physics().robot(m.robot->id);
    setup.check_link = [&pr](const std::string& l) { (void)pr.linkPose(l); };
  } else {
    setup.check_link = [this, id](const std::string& l) { (void)linkPose(LinkRef{id, l}); };
  }
  setup.seed = options_.seed;
  setup.gravity = sim_.physics().options().gravity;
  if (m.robot) setup.urdf = m.robot->model.urdf.get();
  setup.warn = options_.log.warn;
  const std::string owner = (m.robot ? "robot '" : "model '") + m.name + "'";
  const std::string why = sensors_->add(std::move(setup), owner, attach);
  // Left out by its set-up (its spec's own error and an unknown type are not listed, as before).
  if (!why.empty() && spec.error.empty() && findSensorKind(spec)) m.left_out[spec.name] = why;
}

// --- time -----------------------------------------------------------------------------------------

StepWaits Simulator::advance() {
  if (!actor_shapes_.empty()) {
    // Gazebo: World::Step advances the sim time, then Actor::Update places the actor for it,
    // then the physics steps.
    const double t = sim_.time() + sim_.dt();
    for (const ActorShape& s : actor_shapes_) {
      if (s.shape < 0) continue;
      sim_.physics().setStaticShapePose(s.shape,
                                        actor_physics_players_[s.actor].poseAt(t) * s.X_AS);
    }
  }
  sim_.step();
  if (track_contacts_) {
    StepProfile::Scope timed(options_.profile, contacts_row_);
    contacts_.update(sim_.physics(), sim_.time());
  }
  const double t = sim_.time();
  StepWaits waits;
  waits.replies = lockstep_replies_ && reply_schedule_.due(t);
  waits.ticks = lockstep_ticks_ && tick_schedule_.due(t);
  return waits;
}

void Simulator::sense() { sensors_->sense(sim_.time()); }

void Simulator::step(int n) {
  StepProfile* const profile = options_.profile;
  for (int k = 0; k < n; ++k) {
    StepProfile::Scope timed(profile, step_row_);
    if (profile) profile->countStep();
    advance();
    sense();
  }
}

void Simulator::waitFrames() { sensors_->waitFrames(); }

void Simulator::resetSimulation() {
  waitFrames();  // the frame in flight goes out before time jumps back
  sim_.resetSimulation();
  contacts_.reset();
  scene_step_ = ~0ull;  // the step count goes back to one the scene may have been drawn at
  const double t = sim_.time();
  sensors_->restart(t);
  restartLockstep(t);
}

void Simulator::resetWorld() {
  sim_.resetWorld();
  contacts_.reset();
  scene_step_ = ~0ull;  // models moved between steps
}

void Simulator::setLockstep(bool replies, double reply_period, bool ticks, double tick_period) {
  lockstep_replies_ = replies;
  lockstep_ticks_ = ticks;
  reply_schedule_.period = reply_period;
  tick_schedule_.period = tick_period;
  restartLockstep(sim_.time());
}

void Simulator::restartLockstep(double t) {
  // The data at t itself went out before anyone could answer it (start, reset): the first wait
  // is one period later.
  reply_schedule_.next = t + reply_schedule_.period;
  tick_schedule_.next = t + tick_schedule_.period;
}

// --- state ----------------------------------------------------------------------------------------

EntityState Simulator::modelState(ModelId id) const {
  EntityState s;
  if (const PhysicsRobot* p = physicsOf(id)) {
    s.X_WE = p->basePose();
    s.V_WE = p->baseTwist();
    return s;
  }
  if (models_[id].actor >= 0) {
    // Moved by SetWorldPose only, its links have no velocity in Gazebo (Actor::Update).
    s.X_WE = actor_players_[models_[id].actor].poseAt(sim_.physics().time());
    return s;
  }
  for (const ModelDescription& d : world_->models) {
    if (d.name == models_[id].name) s.X_WE = d.X_WM;
  }
  return s;
}

void Simulator::jointStates(ModelId id, JointStates* out) const {
  const SimRobot* r = robot(id);
  if (!r) throw std::out_of_range("model id " + std::to_string(id) + " is not a robot");
  const PhysicsRobot& pr = sim_.physics().robot(r->id);
  const std::size_t n = pr.joints().size();
  out->name.resize(n);
  out->position.resize(n);
  out->velocity.resize(n);
  out->effort.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    out->name[j] = pr.joints()[j].name;
    out->position[j] = pr.jointPosition(static_cast<int>(j));
    out->velocity[j] = pr.jointVelocity(static_cast<int>(j));
    out->effort[j] = pr.jointEffort(static_cast<int>(j));
  }
}

bool Simulator::setCommand(ModelId id, const std::string& controller, double value) {
  SimRobot* r = robot(id);
  if (!r) return false;
  return sim_.controllerManager().setCommand(*r, controller, value);
}

void Simulator::setContactTracking(bool on) {
  if (track_contacts_ && !on) contacts_.reset();
  track_contacts_ = on;
}

std::uint64_t Simulator::contactCount(ModelId id) const {
  const SimRobot* r = robot(id);
  return r ? contacts_.count(r->id) : 0;
}

void Simulator::robotContacts(ModelId id, std::vector<RobotContact>* out) const {
  out->clear();
  const SimRobot* r = robot(id);
  if (r) tianracer_sim::robotContacts(const_cast<PhysicsWorld&>(sim_.physics()), r->id, out);
}

void Simulator::contactNames(RobotId robot, const RobotContact& contact, std::string* link,
                             std::string* other_model, std::string* other_link) const {
  *link = sim_.physics().robot(robot).tree().bodies.at(contact.body).link;
  contacts_.otherOf(sim_.physics(), contact, other_model, other_link);
}

// --- SensorWorld ----------------------------------------------------------------------------------

void Simulator::updateScene() {
  if (scene_step_ == sim_.stepCount()) return;
  for (const Model& m : models_) {
    if (m.robot) updateRobotScene(sim_.physics().robot(m.robot->id), m.scene_bodies, &scene_);
  }
  updateFreeBodyScene(sim_.physics(), &scene_);
  updateActorScene(*world_, &actor_players_, sim_.physics().time(), &scene_);
  scene_step_ = sim_.stepCount();
}

const Scene& Simulator::scene() {
  StepProfile::Scope timed(options_.profile, scene_row_);
  updateScene();
  return scene_;
}

Eigen::Isometry3d Simulator::linkPose(const LinkRef& link) const {
  if (const PhysicsRobot* p = physicsOf(link.model)) return p->linkPose(link.link);
  if (const int a = models_[link.model].actor; a >= 0) {
    for (const LinkDescription& l : world_->actors[a].model.links) {
      if (l.name == link.link)
        return actor_players_[a].poseAt(sim_.physics().time()) * l.X_ML;
    }
  }
  // A static world model: where the world file put it.
  for (const ModelDescription& d : world_->models) {
    if (d.name != models_[link.model].name) continue;
    for (const LinkDescription& l : d.links) {
      if (l.name == link.link) return d.X_WM * l.X_ML;
    }
  }
  throw std::out_of_range("model '" + models_[link.model].name + "' has no link '" + link.link + "'");
}

bool Simulator::linkState(const LinkRef& link, LinkState* state) const {
  const PhysicsRobot* p = physicsOf(link.model);
  if (!p) {  // static: it does not move
    *state = LinkState();
    state->X_WL = linkPose(link);
    return true;
  }
  const PhysicsRobot& pr = *p;
  const auto it = pr.tree().links.find(link.link);
  if (it == pr.tree().links.end() || it->second.first != 0) return false;
  const Twist base = pr.baseTwist();
  state->X_WL = pr.linkPose(link.link);
  state->w_W = base.angular;
  state->v_W = base.linear + base.angular.cross(state->X_WL.translation() -
                                                pr.basePose().translation());
  return true;
}

void Simulator::linkContacts(const LinkRef& link, std::vector<LinkContact>* out) {
  out->clear();
  PhysicsWorld& world = sim_.physics();
  const auto add = [&](const RobotContact& c, const std::string& own) {
    LinkContact b;
    b.own = own;
    std::string other_link;
    contacts_.otherOf(world, c, &b.other, &other_link);
    if (!other_link.empty()) b.other += "::" + other_link;
    b.position_W = c.position_W;
    b.normal_W = c.normal_W;
    b.depth = c.depth;
    b.impulse = c.impulse;
    out->push_back(std::move(b));
  };
  const PhysicsRobot* pr = physicsOf(link.model);
  if (!pr) {
    // A static world model (or one fixed to the world): its link's collisions are static
    // shapes, touched by what rests on or hits them.
    const std::string& name = model(link.model)->name;
    contact_scratch_.clear();
    const auto& owners = contacts_.staticOwners();
    for (int i = 0; i < static_cast<int>(owners.size()); ++i) {
      if (owners[i].first == name && owners[i].second == link.link)
        staticShapeContacts(world, i, &contact_scratch_);
    }
    for (const RobotContact& c : contact_scratch_) add(c, name + "::" + link.link);
    return;
  }
  const auto it = pr->tree().links.find(link.link);
  if (it == pr->tree().links.end()) return;
  if (const SimRobot* r = robot(link.model)) {
    tianracer_sim::robotContacts(world, r->id, &contact_scratch_);
  } else {
    freeBodyContacts(world, world.freeBodyIndex(model(link.model)->name), &contact_scratch_);
  }
  for (const RobotContact& c : contact_scratch_) {
    if (c.body == it->second.first) add(c, pr->name() + "::" + pr->tree().bodies.at(c.body).link);
  }
}

// --- SensorWorld: drives ----------------------------------------------------------------------------

int Simulator::jointIndex(ModelId id, const std::string& joint, std::string* parent_link,
                          std::string* child_link) const {
  const PhysicsRobot* p = model(id) ? physicsOf(id) : nullptr;
  const int i = p ? p->jointIndex(joint) : -1;
  if (i < 0) return -1;
  if (parent_link) *parent_link = p->joints()[i].parent_link;
  if (child_link) *child_link = p->joints()[i].child_link;
  return i;
}

double Simulator::jointPosition(ModelId id, int joint) const {
  return physicsOf(id)->jointPosition(joint);
}

double Simulator::jointVelocity(ModelId id, int joint) const {
  return physicsOf(id)->jointVelocity(joint);
}

void Simulator::setJointVelocity(ModelId id, int joint, double omega, double max_effort) {
  physicsOf(id)->setJointVelocityTarget(joint, omega, max_effort);
}

LinkState Simulator::modelFrameState(ModelId id) const {
  const EntityState e = modelState(id);
  LinkState s;
  s.X_WL = e.X_WE;
  s.v_W = e.V_WE.linear;
  s.w_W = e.V_WE.angular;
  return s;
}

bool Simulator::setModelVelocity(ModelId id, const Eigen::Vector3d& linear_W,
                                 const Eigen::Vector3d& angular_W) {
  PhysicsRobot* p = physicsOf(id);
  if (!p) return false;
  Twist twist;
  twist.linear = linear_W;
  twist.angular = angular_W;
  p->setBaseTwist(twist);
  return true;
}

}  // namespace tianracer_sim
