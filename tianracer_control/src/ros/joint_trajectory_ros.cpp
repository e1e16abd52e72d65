// The ROS side of joint_trajectory_controller (joint_trajectory_controller_impl.h's init):
// <controller>/follow_joint_trajectory (actionlib, control_msgs/FollowJointTrajectory),
// <controller>/command (trajectory_msgs/JointTrajectory), <controller>/state
// (control_msgs/JointTrajectoryControllerState at state_publish_rate) and
// <controller>/query_state (control_msgs/QueryTrajectoryState). Goals, cancels and commands are
// queued by the callbacks and handed to the controller in apply(), in the order they came;
// goal outcomes go out in publish(). query_state samples a copy of the trajectory taken after
// each step, so the service thread never touches the controller.
#include <cmath>
#include <deque>
#include <map>
#include <mutex>

#include <actionlib/server/action_server.h>
#include <control_msgs/FollowJointTrajectoryAction.h>
#include <control_msgs/JointTrajectoryControllerState.h>
#include <control_msgs/QueryTrajectoryState.h>
#include <ros/console.h>
#include <trajectory_msgs/JointTrajectory.h>

#include "tianracer_control/controllers/joint_trajectory_controller.h"
#include "tianracer_control/ros/controller_ros.h"

namespace tianracer_control {

namespace {

using trajectory::GoalId;

trajectory::JointTrajectoryCommand toCommand(const trajectory_msgs::JointTrajectory& msg) {
  trajectory::JointTrajectoryCommand c;
  c.stamp = msg.header.stamp.toSec();
  c.joint_names = msg.joint_names;
  for (const trajectory_msgs::JointTrajectoryPoint& p : msg.points) {
    trajectory::TrajectoryPoint point;
    point.positions = p.positions;
    point.velocities = p.velocities;
    point.accelerations = p.accelerations;
    point.time_from_start = p.time_from_start.toSec();
    c.points.push_back(std::move(point));
  }
  return c;
}

std::vector<trajectory::JointTolerance> toTolerances(
    const std::vector<control_msgs::JointTolerance>& msgs) {
  std::vector<trajectory::JointTolerance> out;
  for (const control_msgs::JointTolerance& m : msgs) {
    out.push_back({m.name, m.position, m.velocity, m.acceleration});
  }
  return out;
}

void fill(trajectory_msgs::JointTrajectoryPoint& point, const trajectory::State& s,
          bool accelerations) {
  point.positions = s.position;
  point.velocities = s.velocity;
  if (accelerations) point.accelerations = s.acceleration;
  point.time_from_start = ros::Duration(s.time_from_start);
}

class JointTrajectoryRos : public ControllerRosSide {
 public:
  using ActionServer = actionlib::ActionServer<control_msgs::FollowJointTrajectoryAction>;
  using GoalHandle = ActionServer::GoalHandle;

  static std::unique_ptr<ControllerRosSide> create(RosSideContext& context) {
    return std::make_unique<JointTrajectoryRos>(context);
  }

  explicit JointTrajectoryRos(RosSideContext& context)
      : controller_(dynamic_cast<JointTrajectoryController&>(context.controller)),
        name_(controller_.name()),
        monitor_period_(1.0 / controller_.options().action_monitor_rate) {
    ros::NodeHandle& nh = context.controller_nh;
    command_sub_ = nh.subscribe<trajectory_msgs::JointTrajectory>(
        "command", 1, [this](const trajectory_msgs::JointTrajectory::ConstPtr& msg) {
          std::lock_guard<std::mutex> lock(mutex_);
          queue_.push_back(Pending{Pending::kCommand, toCommand(*msg), GoalHandle()});
        });
    state_pub_ = nh.advertise<control_msgs::JointTrajectoryControllerState>("state", 1);
    query_srv_ = nh.advertiseService("query_state", &JointTrajectoryRos::onQuery, this);
    server_ = std::make_unique<ActionServer>(
        nh, "follow_joint_trajectory",
        [this](GoalHandle gh) {
          std::lock_guard<std::mutex> lock(mutex_);
          queue_.push_back(Pending{Pending::kGoal, {}, gh});
        },
        [this](GoalHandle gh) {
          std::lock_guard<std::mutex> lock(mutex_);
          queue_.push_back(Pending{Pending::kCancel, {}, gh});
        },
        false);
    server_->start();
  }

  void apply() override {
    std::deque<Pending> queue;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue.swap(queue_);
    }
    for (Pending& p : queue) {
      switch (p.kind) {
        case Pending::kCommand: {  // trajectoryCommandCB
          const auto r = controller_.command(p.command);
          for (const std::string& w : r.warnings) ROS_WARN_STREAM_NAMED(name_, w);
          if (!r.ok()) ROS_ERROR_STREAM_NAMED(name_, r.error);
          break;
        }
        case Pending::kGoal:
          onGoal(p.handle);
          break;
        case Pending::kCancel: {  // cancelCB: only the active goal
          for (const auto& entry : handles_) {
            if (entry.second == p.handle) {
              controller_.cancelGoal(entry.first);
              break;
            }
          }
          break;
        }
      }
      sendOutcomes();  // a preempted goal is canceled before the new one is accepted
    }
  }

  void publish(double t) override {
    sendOutcomes();
    if (controller_.takeStateDue()) {  // publishState
      control_msgs::JointTrajectoryControllerState msg;
      msg.header.stamp = ros::Time(controller_.time());
      msg.joint_names = controller_.jointNames();
      fill(msg.desired, controller_.desiredState(), true);
      fill(msg.actual, controller_.currentState(), false);
      fill(msg.error, controller_.stateError(), false);
      state_pub_.publish(msg);
    }
    const GoalId active = controller_.activeGoal();
    if (active != 0 && t >= next_feedback_) {  // the goal handle's feedback, at the monitor rate
      next_feedback_ = t + monitor_period_;
      auto it = handles_.find(active);
      if (it != handles_.end()) {
        control_msgs::FollowJointTrajectoryFeedback feedback;
        feedback.header.stamp = ros::Time(controller_.time());
        feedback.joint_names = controller_.jointNames();
        fill(feedback.desired, controller_.desiredState(), true);
        fill(feedback.actual, controller_.currentState(), false);
        fill(feedback.error, controller_.stateError(), false);
        it->second.publishFeedback(feedback);
      }
    }
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    if (snapshot_version_ != controller_.trajectoryVersion() || !snapshot_valid_) {
      snapshot_ = controller_.currentTrajectory();
      snapshot_version_ = controller_.trajectoryVersion();
    }
    snapshot_valid_ = controller_.running();
    snapshot_time_ = controller_.time();
    snapshot_uptime_ = controller_.uptime();
  }

  void clear() override {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.clear();
  }

  std::vector<std::string> commandTopics() const override { return {command_sub_.getTopic()}; }

 private:
  struct Pending {
    enum Kind { kCommand, kGoal, kCancel } kind;
    trajectory::JointTrajectoryCommand command;
    GoalHandle handle;
  };

  void onGoal(GoalHandle gh) {  // goalCB
    const auto goal = gh.getGoal();
    trajectory::GoalTolerances tolerances;
    tolerances.path_tolerance = toTolerances(goal->path_tolerance);
    tolerances.goal_tolerance = toTolerances(goal->goal_tolerance);
    tolerances.goal_time_tolerance = goal->goal_time_tolerance.toSec();
    const GoalId id = ++last_goal_;
    const auto r = controller_.startGoal(id, toCommand(goal->trajectory), tolerances);
    for (const std::string& w : r.warnings) ROS_WARN_STREAM_NAMED(name_, w);
    if (!r.ok()) {
      ROS_ERROR_STREAM_NAMED(name_, r.error);
      control_msgs::FollowJointTrajectoryResult result;
      result.error_code = r.error_code;
      // upstream gives the reason only with INVALID_GOAL (updateTrajectoryCommand's)
      if (r.error_code == control_msgs::FollowJointTrajectoryResult::INVALID_GOAL) {
        result.error_string = r.error;
      }
      gh.setRejected(result);
      return;
    }
    sendOutcomes();  // the preempted goal first
    gh.setAccepted();
    handles_[id] = gh;
  }

  void sendOutcomes() {
    for (const auto& e : controller_.takeGoalEvents()) {
      auto it = handles_.find(e.goal);
      if (it == handles_.end()) continue;
      control_msgs::FollowJointTrajectoryResult result;
      result.error_code = e.error_code;
      result.error_string = e.error_string;
      using Kind = JointTrajectoryController::GoalEvent::Kind;
      switch (e.kind) {
        case Kind::kSucceeded:
          it->second.setSucceeded(result);
          break;
        case Kind::kAborted:
          it->second.setAborted(result);
          break;
        case Kind::kCanceled:
          it->second.setCanceled();
          break;
      }
      handles_.erase(it);
    }
  }

  bool onQuery(control_msgs::QueryTrajectoryState::Request& req,
               control_msgs::QueryTrajectoryState::Response& resp) {
    std::lock_guard<std::mutex> lock(snapshot_mutex_);
    if (!snapshot_valid_) {
      ROS_ERROR_NAMED(name_, "Can't sample trajectory. Controller is not running.");
      return false;
    }
    trajectory::State state;
    std::string error;
    const double sample = snapshot_uptime_ + (req.time.toSec() - snapshot_time_);
    if (!JointTrajectoryController::sampleTrajectory(snapshot_, sample, state, error)) {
      ROS_ERROR_STREAM_NAMED(name_, error);
      return false;
    }
    resp.name = controller_.jointNames();  // fixed after construction
    resp.position = state.position;
    resp.velocity = state.velocity;
    resp.acceleration = state.acceleration;
    return true;
  }

  JointTrajectoryController& controller_;
  const std::string name_;
  const double monitor_period_;
  ros::Subscriber command_sub_;
  ros::Publisher state_pub_;
  ros::ServiceServer query_srv_;
  std::unique_ptr<ActionServer> server_;

  std::mutex mutex_;  // the callbacks' queue
  std::deque<Pending> queue_;

  GoalId last_goal_ = 0;                   // the sim loop's
  std::map<GoalId, GoalHandle> handles_;   // goals accepted and not finished
  double next_feedback_ = 0.0;

  std::mutex snapshot_mutex_;  // query_state's copy
  trajectory::Trajectory snapshot_;
  std::uint64_t snapshot_version_ = 0;
  bool snapshot_valid_ = false;
  double snapshot_time_ = 0.0;
  double snapshot_uptime_ = 0.0;
};

TIANRACER_CONTROLLER_ROS_SIDE(JointTrajectoryController::kPositionType, JointTrajectoryRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(JointTrajectoryController::kVelocityType, JointTrajectoryRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(JointTrajectoryController::kEffortType, JointTrajectoryRos::create);

}  // namespace

}  // namespace tianracer_control
