// The ROS side of gripper_action_controller (gripper_action_controller_impl.h's init):
// <controller>/gripper_cmd (actionlib, control_msgs/GripperCommand). Goals and cancels are
// queued by the callbacks and handed to the controller in apply(), in the order they came; the
// results (position, effort, stalled, reached_goal) go out in publish().
#include <deque>
#include <map>
#include <mutex>

#include <actionlib/server/action_server.h>
#include <control_msgs/GripperCommandAction.h>
#include <ros/console.h>

#include "tianracer_control/controllers/gripper_action_controller.h"
#include "tianracer_control/ros/controller_ros.h"

namespace tianracer_control {

namespace {

class GripperActionRos : public ControllerRosSide {
 public:
  using ActionServer = actionlib::ActionServer<control_msgs::GripperCommandAction>;
  using GoalHandle = ActionServer::GoalHandle;
  using GoalId = GripperActionController::GoalId;

  static std::unique_ptr<ControllerRosSide> create(RosSideContext& context) {
    return std::make_unique<GripperActionRos>(context);
  }

  explicit GripperActionRos(RosSideContext& context)
      : controller_(dynamic_cast<GripperActionController&>(context.controller)),
        name_(controller_.name()) {
    server_ = std::make_unique<ActionServer>(
        context.controller_nh, "gripper_cmd",
        [this](GoalHandle gh) {
          std::lock_guard<std::mutex> lock(mutex_);
          queue_.push_back({true, gh});
        },
        [this](GoalHandle gh) {
          std::lock_guard<std::mutex> lock(mutex_);
          queue_.push_back({false, gh});
        },
        false);
    server_->start();
  }

  void apply() override {
    std::deque<std::pair<bool, GoalHandle>> queue;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue.swap(queue_);
    }
    for (auto& entry : queue) {
      GoalHandle& gh = entry.second;
      if (entry.first) {  // goalCB
        const auto goal = gh.getGoal();
        const GoalId id = ++last_goal_;
        const std::string error =
            controller_.startGoal(id, goal->command.position, goal->command.max_effort);
        if (!error.empty()) {
          ROS_ERROR_STREAM_NAMED(name_, error);
          gh.setRejected(control_msgs::GripperCommandResult());
          continue;
        }
        sendOutcomes();  // the preempted goal first
        gh.setAccepted();
        handles_[id] = gh;
      } else {  // cancelCB: only the active goal
        for (const auto& h : handles_) {
          if (h.second == gh) {
            controller_.cancelGoal(h.first);
            break;
          }
        }
        sendOutcomes();
      }
    }
  }

  void publish(double) override { sendOutcomes(); }

  void clear() override {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.clear();
  }

 private:
  void sendOutcomes() {
    for (const auto& e : controller_.takeGoalEvents()) {
      auto it = handles_.find(e.goal);
      if (it == handles_.end()) continue;
      control_msgs::GripperCommandResult result;
      result.position = e.position;
      result.effort = e.effort;
      result.stalled = e.stalled;
      result.reached_goal = e.reached_goal;
      using Kind = GripperActionController::GoalEvent::Kind;
      switch (e.kind) {
        case Kind::kSucceeded:
          it->second.setSucceeded(result);
          break;
        case Kind::kAborted:
          it->second.setAborted(result);
          break;
        case Kind::kCanceled:
          it->second.setCanceled(result);
          break;
      }
      handles_.erase(it);
    }
  }

  GripperActionController& controller_;
  const std::string name_;
  std::unique_ptr<ActionServer> server_;
  std::mutex mutex_;
  std::deque<std::pair<bool, GoalHandle>> queue_;
  GoalId last_goal_ = 0;
  std::map<GoalId, GoalHandle> handles_;
};

TIANRACER_CONTROLLER_ROS_SIDE(GripperActionController::kPositionType, GripperActionRos::create);
TIANRACER_CONTROLLER_ROS_SIDE(GripperActionController::kEffortType, GripperActionRos::create);

}  // namespace

}  // namespace tianracer_control
