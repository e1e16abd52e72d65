// The round-number car the control unit tests compute by hand: L = 0.25, T = 0.14
// (T/2 = 0.07), r = 0.05, Tr = 0.16, max steering 0.6 rad.
#ifndef TIANRACER_CONTROL_TEST_TEST_GEOMETRY_H
#define TIANRACER_CONTROL_TEST_TEST_GEOMETRY_H

#include "tianracer_control/ackermann.h"

namespace tianracer_control {
namespace test {

inline AckermannGeometry geometry() {
  AckermannGeometry g;
  g.wheelbase = 0.25;
  g.hinge_separation = 0.14;
  g.wheel_radius = 0.05;
  g.rear_track = 0.16;
  g.max_steering_angle = 0.6;
  return g;
}

}  // namespace test
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TEST_TEST_GEOMETRY_H
