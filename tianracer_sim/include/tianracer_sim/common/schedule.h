// Things done on a sim-time schedule (sensor samples, joint_states, /clock, lockstep waits),
// and the per-sensor counts the status line reports. ROS-free.
#ifndef TIANRACER_SIM_COMMON_SCHEDULE_H
#define TIANRACER_SIM_COMMON_SCHEDULE_H

#include <cstdint>
#include <string>

namespace tianracer_sim {

/// Something done on a sim-time schedule: due when time >= next; next advances by period (a
/// reset restarts it; a long pause does not cause a burst).
struct Schedule {
  double period = 0.0;  // s; 0 = every step
  double next = 0.0;
  bool due(double t);
  void restart(double t) { next = t; }
};

/// Samples of one sensor since the last status report, against the target rate.
struct SensorStat {
  std::string name;  // what the status line calls it, e.g. "/scan"
  double target = 0.0;
  std::uint64_t count = 0;
  std::uint64_t skipped = 0;  // due while nobody wanted it (nothing computed)
  std::uint64_t renders = 0;  // frames rendered / scans cast in total
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_SCHEDULE_H
