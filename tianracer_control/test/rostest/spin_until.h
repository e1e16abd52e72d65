// The rostests' wait: spin ROS callbacks until done() holds or a wall-clock bound passes. The
// bound only stops a test whose node stopped; it never measures anything.
#ifndef TIANRACER_CONTROL_TEST_ROSTEST_SPIN_UNTIL_H
#define TIANRACER_CONTROL_TEST_ROSTEST_SPIN_UNTIL_H

#include <functional>

#include <ros/ros.h>

namespace tianracer_control {
namespace test {

/// done() after spinning, polled every `poll` seconds for at most `seconds` (wall time).
inline bool spinUntil(const std::function<bool()>& done, double seconds, double poll) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < end) {
    ros::spinOnce();
    if (done()) return true;
    ros::WallDuration(poll).sleep();
  }
  return done();
}

}  // namespace test
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TEST_ROSTEST_SPIN_UNTIL_H
