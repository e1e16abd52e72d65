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
  /// The word "commands" in ticks: every loaded controller's command topic is a tick topic,
  /// as controllers come and go (Lockstep::setCommandTopics()).
  bool tick_commands = false;
  double tick_period = 0.02;  // s of sim time
  double timeout = 1.0;       // wall s; past it the step goes on without the topic
  bool enabled() const { return !replies.empty() || !ticks.empty() || tick_commands; }
  bool waitsForTicks() const { return !ticks.empty() || tick_commands; }
};

/// Reads ~lockstep/{replies,reply_period,ticks,tick_period,timeout}. Throws
/// std::runtime_error naming the parameter and the value.
LockstepOptions lockstepOptions(const ros::NodeHandle& pnh);

class Lockstep {
 public:
  /// Subscribes (any type) to the topics on `nh`, whose callbacks run on `queue`.
  Lockstep(ros::NodeHandle nh, ros::CallbackQueue* queue, LockstepOptions options);

  // Which steps wait is the Simulator's decision (Simulator::setLockstep(), advance()).
  /// Forgets what arrived so far: the wait after this call needs a message sent after it.
  void markReplies() { mark(replies_); }
  void markTicks() { mark(ticks_); }
  /// Serves `queue` until each topic of the group has a message since its mark, or the wall
  /// timeout. A topic that timed out is not waited for again until its next message or a new
  /// publisher (a driver that stopped costs one timeout, not one per period; one that starts
  /// later is waited for from its next tick on); reported once per topic. A topic nobody
  /// publishes on is not waited for.
  void awaitReplies(double t) { await(replies_, t, "the sensor data of"); }
  void awaitTicks(double t) { await(ticks_, t, "the /clock of"); }
  /// With tick_commands: the controllers' command topics now (start-up, spawn, delete_model,
  /// controller_manager's load and unload). A topic added after start-up is waited for from
  /// its first message on (a controller nobody commands yet costs no timeout); one gone is no
  /// longer waited for.
  void setCommandTopics(const std::vector<std::string>& topics);
  /// The tick topics waited for (resolved names), in order.
  std::vector<std::string> tickTopics() const;
  /// With tick topics, /clock goes out at tick steps only (every tick step does), so that a
  /// node starting mid-run reads a time on the tick grid and its sim-time timers, which count
  /// from the time they start at (roscpp's and rospy's), tick on the grid too.
  bool clockOnTicksOnly() const { return options_.waitsForTicks(); }
  const LockstepOptions& options() const { return options_; }
  std::uint64_t timeouts() const { return timeouts_; }

 private:
  struct Topic {
    std::string name;
    ros::Subscriber sub;
    bool arrived = false;
    bool absent = false;  // timed out; waited for again once a message or a publisher arrives
    bool reported = false;
    bool command = false;  // from setCommandTopics(), not named in ~lockstep/ticks
    std::uint32_t publishers = 0;  // at the last mark
  };
  using Group = std::vector<std::unique_ptr<Topic>>;
  void subscribe(ros::NodeHandle& nh, const std::vector<std::string>& names, Group* group);
  std::unique_ptr<Topic> makeTopic(ros::NodeHandle& nh, const std::string& name);
  void mark(Group& group);
  void await(Group& group, double t, const char* after);

  ros::NodeHandle nh_;
  ros::CallbackQueue* queue_;
  LockstepOptions options_;
  bool started_ = false;  // setCommandTopics() ran once
  Group replies_, ticks_;
  std::uint64_t timeouts_ = 0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_LOCKSTEP_H
