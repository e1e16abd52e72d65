#include "tianracer_sim/ros/sim_node.h"

#include <cstdio>
#include <set>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/package.h>
#include <rosgraph_msgs/Clock.h>

#include "tianracer_sim/common/diagnostic.h"
#include "tianracer_sim/ros/params.h"
#include "tianracer_sim/ros/plugins/sensor_publisher.h"

namespace tianracer_sim {

namespace {

/// The pace's waits serve the node's commands and services.
Pacer::Hooks servingQueue(ros::CallbackQueue* queue) {
  Pacer::Hooks hooks;
  hooks.serve = [queue](double s) { queue->callAvailable(ros::WallDuration(s)); };
  hooks.sleep = [](double s) { ros::WallDuration(s).sleep(); };
  return hooks;
}

}  // namespace

void SimNode::warnOnce(const std::string& text) { warnOnceOnRosout(text); }

SimNode::SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, SimNodeCore core)
    : nh_(nh),
      pnh_(pnh),
      profile_(std::move(core.profile)),
      startup_(std::move(core.startup)),
      root_("/"),
      world_options_(std::move(core.world_options)),
      sim_(std::move(core.sim)),
      real_time_factor_(core.real_time_factor),
      pacer_(servingQueue(&queue_)) {
  if (!sim_) throw std::invalid_argument("SimNode: no Simulator given");
  nh_.setCallbackQueue(&queue_);
  pnh_.setCallbackQueue(&queue_);
  root_.setCallbackQueue(&queue_);
  checkSensorPublishers();  // every sensor kind has its publisher (registered beside each)
  setUpProfile();

  const NodeParams& params = core.params;
  // /clock every 5 ms of sim time by default: running 10x faster than real time, 1 kHz would
  // be 10,000 messages a second to every node, more than a rospy node can read.
  clock_schedule_.period = params.clock_rate > 0.0 ? 1.0 / params.clock_rate : 0.0;
  ground_truth_rate_ = params.ground_truth_rate;
  status_period_ = params.status_period;
  // Sensors on the world's models (and spawn_sdf_model's) publish as a robot's do.
  sim_->attachWorldSensors([this](SimSensor& sensor) { attachWorldSensor(sensor); });

  // /clock first, so that nodes waiting for sim time see it as soon as we step.
  nh_.setParam("/use_sim_time", true);
  clock_pub_ = root_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  // Not gazebo_ros's: gazebo_ros's gzserver stand-in turns it off (~diagnostics false).
  if (params.diagnostics) {
    // Its contact counts need the contacts tracked while someone reads /diagnostics.
    diagnostics_pub_ = root_.advertise<diagnostic_msgs::DiagnosticArray>(
        "/diagnostics", 10, [this](const ros::SingleSubscriberPublisher&) { ++diagnostics_readers_; },
        [this](const ros::SingleSubscriberPublisher&) { --diagnostics_readers_; });
  }
  contacts_ = std::make_unique<ContactPublisher>(*sim_);

  bool several = false;
  const std::vector<std::string> robot_names = getNameList(pnh_, "robots", &several);
  if (!several) {
    loadRobot(pnh_, "");
  } else if (robot_names.empty()) {
    // As `gzserver x.world`: the world runs alone until robots are spawned.
    ROS_INFO("no robot at start (%s is empty): robots arrive through "
             "%s/spawn_urdf_model", pnh_.resolveName("robots").c_str(),
             params.gazebo_namespace.c_str());
  }
  for (const std::string& name : robot_names) loadRobot(ros::NodeHandle(pnh_, name), name);

  LockstepOptions lockstep = lockstepOptions(pnh_);
  if (lockstep.enabled()) {
    lockstep_ = std::make_unique<Lockstep>(root_, &queue_, lockstep);
    updateCommandTopics();
    sim_->setLockstep(!lockstep.replies.empty(), lockstep.reply_period, lockstep.waitsForTicks(),
                      lockstep.tick_period);
    ROS_INFO("lockstep: each %g s waits for %zu reply topics, each %g s for %zu tick topics%s "
             "(timeout %g s wall)", lockstep.reply_period, lockstep.replies.size(),
             lockstep.tick_period, lockstep_->tickTopics().size(),
             lockstep.tick_commands ? " (the controllers' command topics as they come and go)" : "",
             lockstep.timeout);
  }

  ros::NodeHandle gazebo(params.gazebo_namespace);
  gazebo.setCallbackQueue(&queue_);
  GazeboInterface::Options gazebo_options;
  gazebo_options.states_rate = params.gazebo_states_rate.value_or(gazebo_options.states_rate);
  gazebo_options.enable_ros_network = params.enable_ros_network;
  gazebo_ = std::make_unique<GazeboInterface>(gazebo, *sim_, gazebo_options,
                                             static_cast<ModelSpawner*>(this),
                                             [this] { afterReset(); });

  StepBridge::Hooks step_hooks;
  step_hooks.begin = [this] {
    if (!initial_published_) publishInitial();
  };
  step_hooks.step = [this] { stepOnce(); };
  step_hooks.finish = [this] {
    sim_->waitFrames();  // the last step's camera frames are out
    const bool grid = lockstep_ && lockstep_->clockOnTicksOnly();
    if (clock_published_ != sim_->time() && !grid) publishClock();
  };
  // ~step and ~step_and_wait are not gazebo_ros's: gazebo_ros's gzserver stand-in turns them
  // off (~step_services false) so that /gazebo offers exactly gazebo_ros's interface.
  if (params.step_services) step_ = std::make_unique<StepBridge>(pnh_, *sim_, &queue_, step_hooks);

  startupMark("Gazebo interface, lockstep, services");
  logStartup();
  ROS_INFO("tianracer_sim: step %.4f s, real_time_factor %g%s, %s", sim_->dt(), real_time_factor_,
           real_time_factor_ == 0.0 ? " (as fast as possible)" : "",
           sim_->paused() ? "paused" : "running");
}

SimNode::~SimNode() {
  if (profile_) {
    // On stdout: after Ctrl-C roscpp has shut rosconsole down before the node goes.
    std::printf("step profile (~profile):\n%s", profile_->table().c_str());
    std::fflush(stdout);
  }
  step_.reset();    // answers the calls still waiting
  robots_.clear();  // command subscribers point into the controllers
  sim_.reset();     // the frame in flight goes out while the node still exists
}

void SimNode::updateCommandTopics() {
  if (!lockstep_) return;
  std::vector<std::string> topics;
  for (const auto& robot : robots_) {
    for (const std::string& t : robot->commandTopics()) topics.push_back(t);
  }
  lockstep_->setCommandTopics(topics);
}

void SimNode::publishClock() {
  StepProfile::Scope timed(profile_.get(), rows_.clock);
  rosgraph_msgs::Clock clock;
  clock.clock = ros::Time(sim_->time());
  clock_pub_.publish(clock);
  clock_published_ = sim_->time();
}

void SimNode::publishInitial() {
  // Started paused, the state at the start time goes out when the physics first runs (unpause
  // or ~step; Gazebo publishes nothing while paused): then every node connected by then gets
  // it, and a node that connects a moment sooner or later cannot change what it receives (the
  // wheel odometry node's first joint_states: the determinism rostest). With lockstep replies
  // the driver's answer to it is awaited as at any reply step.
  const bool replies = lockstep_ && !lockstep_->options().replies.empty();
  if (replies) lockstep_->markReplies();
  publishDue(!replies);
  if (replies) {
    lockstep_->awaitReplies(sim_->time());
    publishClock();
  }
  initial_published_ = true;
}

void SimNode::publishDue(bool clock) {
  const double t = sim_->time();
  if (clock_schedule_.due(t) && clock) publishClock();
  for (const auto& robot : robots_) robot->publish(t);
  sim_->sense();
}

void SimNode::stepOnce() {
  StepProfile* const profile = profile_.get();
  StepProfile::Scope timed(profile, rows_.step);
  if (profile) profile->countStep();
  {
    StepProfile::Scope part(profile, rows_.commands);
    for (const auto& robot : robots_) robot->applyCommands();
    gazebo_->beforeStep();
  }
  // Contacts are tracked only while someone reads them (Simulator::setContactTracking).
  sim_->setContactTracking(contacts_->subscribed() || diagnostics_readers_ > 0);
  const StepWaits waits = sim_->advance();
  {
    StepProfile::Scope part(profile, rows_.contact_msgs);
    contacts_->publish(sim_->time());
  }
  const double t = sim_->time();
  // With tick topics /clock keeps to the tick grid (Lockstep::clockOnTicksOnly()).
  const bool grid = lockstep_ && lockstep_->clockOnTicksOnly();
  if (!waits.replies && !waits.ticks) {
    publishDue(!grid);
  } else {
    // The driver answers this step's sensor data before the clock moves on to this step, so
    // that nodes on sim-time timers (the cmd_vel node) tick with its answer in hand.
    if (waits.replies) lockstep_->markReplies();
    publishDue(false);
    if (waits.replies) {
      StepProfile::Scope part(profile, rows_.lockstep);
      lockstep_->awaitReplies(t);
    }
    if (waits.ticks) lockstep_->markTicks();
    if (waits.ticks || !grid) publishClock();
    if (waits.ticks) {
      StepProfile::Scope part(profile, rows_.lockstep);
      lockstep_->awaitTicks(t);
    }
  }
  StepProfile::Scope part(profile, rows_.gazebo_states);
  gazebo_->afterStep();
}

void SimNode::run() {
  publishClock();
  // Running from the start, the start state goes out at once (nobody may be connected yet, so
  // no answer is awaited); started paused, at the first step (publishInitial()).
  if (!sim_->paused()) {
    publishDue();
    initial_published_ = true;
  }
  bool first_step = true;  // its time is logged
  status_wall_ = ros::WallTime::now();
  status_sim_ = sim_->time();
  bool paused_clock = false;  // the paused time went out on /clock
  while (ros::ok()) {
    {
      StepProfile::Scope timed(profile_.get(), rows_.callbacks);
      queue_.callAvailable(ros::WallDuration(0.0));
    }
    if (step_ && step_->serve()) {  // ~step and ~step_and_wait calls (they pause the simulation)
      publishStatus();
      continue;
    }
    if (sim_->paused()) {
      // /clock is throttled (~clock_rate): on pausing, the paused time goes out once more, so
      // that every node's clock reaches it and a client can wait for exactly that time.
      // With lockstep ticks /clock keeps to the tick grid (Lockstep::clockOnTicksOnly()): a
      // paused time off the grid is not published (a node started now would tick off the grid).
      const bool grid = lockstep_ && lockstep_->clockOnTicksOnly();
      if (!paused_clock && !(grid && clock_published_ != sim_->time())) publishClock();
      paused_clock = true;
      queue_.callAvailable(ros::WallDuration(0.01));
      publishStatus();
      pacer_.restart();
      continue;
    }
    paused_clock = false;
    if (!initial_published_) publishInitial();
    pacer_.beginStep(sim_->time());
    if (first_step) {
      const auto t0 = std::chrono::steady_clock::now();
      stepOnce();
      ROS_INFO("first step: %.1f ms",
               std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      first_step = false;
    } else {
      stepOnce();
    }
    if ((sim_->stepCount() & 255) == 0) {
      StepProfile::Scope timed(profile_.get(), rows_.status);
      publishStatus();
    }
    // set_physics_properties may have changed the pace (max_update_rate or the step).
    real_time_factor_ = sim_->properties().maxUpdateRate() * sim_->dt();
    pacer_.endStep(sim_->time(), real_time_factor_);
  }
}

tf2_ros::StaticTransformBroadcaster& SimNode::staticTf() {
  if (!static_tf_) static_tf_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
  return *static_tf_;
}

void SimNode::afterReset() {
  const double t = sim_->time();
  for (const auto& robot : robots_) {
    robot->clearCommands();  // what came before the reset is not applied after it
    robot->restart(t);
  }
  clock_schedule_.restart(t);
  pacer_.restart();
  publishClock();
}

}  // namespace tianracer_sim
