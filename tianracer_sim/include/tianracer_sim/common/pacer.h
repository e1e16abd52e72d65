// Holding sim time to wall time at a real-time factor, as Gazebo's physics loop does with
// max_update_rate (gazebo/physics/World.cc, World::Step: it sleeps until the step's wall time).
// ROS-free: the node passes how it waits (serving its callbacks meanwhile).
#ifndef TIANRACER_SIM_COMMON_PACER_H
#define TIANRACER_SIM_COMMON_PACER_H

#include <chrono>
#include <functional>

namespace tianracer_sim {

class Pacer {
 public:
  using Clock = std::chrono::steady_clock;
  struct Hooks {
    /// Waits up to `seconds`, doing other work meanwhile; may return sooner.
    std::function<void(double seconds)> serve;
    /// Waits `seconds` (after serve() returned sooner).
    std::function<void(double seconds)> sleep;
    std::function<Clock::time_point()> now = [] { return Clock::now(); };
  };
  explicit Pacer(Hooks hooks) : hooks_(std::move(hooks)) {}

  /// The next step measures from its own start (after a pause, a reset or falling behind).
  void restart() { restart_ = true; }
  /// Before a step from sim time `t`.
  void beginStep(double t);
  /// After the step reached sim time `t`, at `factor` x real time (0: as fast as possible):
  /// waits until the wall time of `t`. More than 0.5 s behind, it does not race to catch up
  /// but measures again from the next step. A changed factor measures from `t`.
  void endStep(double t, double factor);

 private:
  Hooks hooks_;
  bool restart_ = true;
  double factor_ = -1.0;  // none yet
  Clock::time_point wall0_;
  double sim0_ = 0.0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_PACER_H
