// What the sensor benchmarks share: the 3D lidar they scan with and the clock they time with.
#ifndef TIANRACER_SIM_BENCH_BENCH_SUPPORT_H
#define TIANRACER_SIM_BENCH_BENCH_SUPPORT_H

#include <cmath>
#include <ctime>

#include "tianracer_sim/plugins/ray/ray_sensor.h"

namespace tianracer_sim {
namespace bench {

/// Makes `v` a 16 x 1800 velodyne: 360 deg (the last beam not repeating the first), +-15 deg,
/// 0.4 - 100 m, cloud noise 0.008. Its other fields (name, rate, 2D noise) stay as they are.
inline void makeVelodyne16(RaySensorConfig& v) {
  v.samples = 1800;
  v.min_angle = -M_PI;
  v.max_angle = M_PI * (1.0 - 2.0 / 1800);
  v.vertical_samples = 16;
  v.vertical_min_angle = -0.2617993878;
  v.vertical_max_angle = 0.2617993878;
  v.range_min = 0.4;
  v.range_max = 100.0;
  v.velodyne = true;
  v.cloud_noise = 0.008;
}

/// This thread's CPU time (s): on a shared machine wall time measures the other jobs' load.
inline double threadCpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

}  // namespace bench
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_BENCH_BENCH_SUPPORT_H
