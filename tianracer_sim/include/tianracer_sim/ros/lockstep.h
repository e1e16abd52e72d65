// Lockstep with the nodes that drive the car: at real_time_factor 0 the simulator waits, each
// control period of sim time, for their answer, so that a run is repeatable however slowly they
// react in wall time. docs/simulator.md, Lockstep.
#ifndef TIANRACER_SIM_ROS_LOCKSTEP_H
#define TIANRACER_SIM_ROS_LOCKSTEP_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>


namespace tianracer_sim {

struct LockstepOptions {
  /// Topics a driver publishes in answer to the sensor data of each reply period (e.g. /cmd_vel
  /// answering the 50 Hz ground truth). Waited for before that step's /clock goes out.
  std::vector<std::string> replies;
  double reply_period = 0.02;  // s of sim time
  /// Topics that nodes publish on a sim-time timer of tick_period (e.g. the cmd_vel node's
  /// controller commands). Waited for after the /clock of each tick.
  std::vector<std::string> ticks;
  double tick_period = 0.02;  // s of sim time
  double timeout = 1.0;       // wall s; past it the step goes on without the topic
  bool enabled() const { return !replies.empty() || !ticks.empty(); }
};

/// Reads ~lockstep/{replies,reply_period,ticks,tick_period,timeout}; the word "commands" in
/// ticks stands for `command_topics` (every controller's command topic). Throws
/// std::runtime_error naming the parameter and the value.
LockstepOptions lockstepOptions(const ros::NodeHandle& pnh,
                                const std::vector<std::string>& command_topics);

class Lockstep {
 public:
  /// Subscribes (any type) to the topics on `nh`, whose callbacks run on `queue`.
  Lockstep(ros::NodeHandle nh, ros::CallbackQueue* queue, LockstepOptions options);

  // Which steps wait is the Simulator's decision (Simulator::setLockstep(), advance()).
  /// Forgets what arrived so far: the wait after this call needs a message sent after it.
  void markReplies() { mark(replies_); }
  void markTicks() { mark(ticks_); }
  /// Serves `queue` until each topic of the group has a message since its mark, or the wall
  /// timeout. A topic that timed out is not waited for again until its next message (a driver
  /// that stopped costs one timeout, not one per period); reported once per topic.
  void awaitReplies(double t) { await(replies_, t, "the sensor data of"); }
  void awaitTicks(double t) { await(ticks_, t, "the /clock of"); }
  const LockstepOptions& options() const { return options_; }
  std::uint64_t timeouts() const { return timeouts_; }

 private:
  struct Topic {
    std::string name;
    ros::Subscriber sub;
    bool arrived = false;
    bool absent = false;  // timed out; waited for again once a message arrives
    bool reported = false;
  };
  using Group = std::vector<std::unique_ptr<Topic>>;
  void subscribe(ros::NodeHandle& nh, const std::vector<std::string>& names, Group* group);
  void mark(Group& group);
  void await(Group& group, double t, const char* after);

  ros::CallbackQueue* queue_;
  LockstepOptions options_;
  Group replies_, ticks_;
  std::uint64_t timeouts_ = 0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_LOCKSTEP_H
