// The lidar the lidar and message tests compute against.
#ifndef TIANRACER_SIM_TEST_LIDAR_TEST_SUPPORT_H
#define TIANRACER_SIM_TEST_LIDAR_TEST_SUPPORT_H

#include <string>

#include "tianracer_sim/plugins/ray/ray_sensor.h"

namespace tianracer_sim {
namespace test {

/// The seed's hokuyo: 1081 beams over +-135 deg, 0.1 - 10 m at 1 cm, in frame "lidar", 40 Hz;
/// noise off unless a test sets it.
inline RaySensorConfig seedHokuyo() {
  RaySensorConfig c;
  c.name = "hokuyo_sensor";
  c.link = "lidar";
  c.update_rate = 40;
  c.samples = 1081;
  c.min_angle = -2.3561944902;
  c.max_angle = 2.3561944902;
  c.range_min = 0.1;
  c.range_max = 10.0;
  c.range_resolution = 0.01;
  c.frame_name = "lidar";
  return c;
}

}  // namespace test
}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_TEST_LIDAR_TEST_SUPPORT_H
