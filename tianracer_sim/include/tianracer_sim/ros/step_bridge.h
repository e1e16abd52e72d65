// Step-locked control from ROS: the node's ~step service (tianracer_sim/Step) and
// ~step_and_wait action (tianracer_sim/StepAndWait), what gazebo_ros_pkgs PR #1280 proposed
// for Gazebo (a step_control service). A call pauses the simulation (if it runs), makes N
// steps exactly as the run loop makes them, and answers once the sensor messages of the last
// step are published. docs/gazebo_interface.md (Stepping).
//
// Threads: the service and the action server run on a callback queue and thread of their own,
// so that a call can wait; the node's run loop carries the steps out (serve()), between its
// other callbacks, and wakes the waiting call.
#ifndef TIANRACER_SIM_ROS_STEP_BRIDGE_H
#define TIANRACER_SIM_ROS_STEP_BRIDGE_H

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <actionlib/server/simple_action_server.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "tianracer_sim/StepAndWaitAction.h"
#include "tianracer_sim/Step.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {

class StepBridge {
 public:
  /// What one step is, and what ends a call; all run on the node's run loop.
  struct Hooks {
    std::function<void()> begin;   // before a call's first step (what is still to go out)
    std::function<void()> step;    // one step as the run loop makes it
    std::function<void()> finish;  // after the last: frames out, /clock of the last step
  };

  /// Advertises <pnh>/step and <pnh>/step_and_wait; `wake` is the node's queue (a posted
  /// call wakes its run loop at once).
  StepBridge(const ros::NodeHandle& pnh, Simulator& sim, ros::CallbackQueue* wake, Hooks hooks);
  /// Calls still waiting are answered with success false.
  ~StepBridge();
  StepBridge(const StepBridge&) = delete;
  StepBridge& operator=(const StepBridge&) = delete;

  /// From the run loop: carries out the calls waiting, in the order they came (the
  /// simulation is paused first). Returns whether it stepped.
  bool serve();

 private:
  struct Request {
    std::uint32_t steps = 0;
    std::uint32_t done = 0;
    double time = 0.0;      // sim time after the steps done so far
    bool cancel = false;    // set by the caller's thread
    bool finished = false;  // set by the run loop
    bool success = false;
    std::string message;
    double sim_time = 0.0;
    std::uint64_t step_count = 0;
  };
  /// Queues the request, wakes the run loop and waits until it is finished (or the node ends);
  /// `progress` is called on the caller's thread every 0.1 s (wall) and whenever steps are
  /// done, with a copy of the request; it returns true to cancel the rest.
  void call(const std::shared_ptr<Request>& r,
            const std::function<bool(const Request&)>& progress = {});
  bool onStep(Step::Request& req, Step::Response& res);
  void onStepAndWait(const StepAndWaitGoalConstPtr& goal);

  Simulator& sim_;
  ros::CallbackQueue* wake_;
  Hooks hooks_;
  ros::CallbackQueue queue_;  // the service and the action server
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  ros::ServiceServer service_;
  std::unique_ptr<actionlib::SimpleActionServer<StepAndWaitAction>> action_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::shared_ptr<Request>> pending_;
  bool stopping_ = false;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_STEP_BRIDGE_H
