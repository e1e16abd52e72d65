// tianracer_sim_node: the simulator. Configuration errors end it with exit code 1 and a
// message naming the parameter, file or controller.
#include <memory>

#include <ros/ros.h>

#include "tianracer_sim/ros/sim_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "tianracer_sim");
  // Held for the whole run: when a failed SimNode drops the last NodeHandle, roscpp shuts
  // down and the error below would never be printed.
  ros::NodeHandle keep_alive;
  std::unique_ptr<tianracer_sim::SimNode> node;
  try {
    node = std::make_unique<tianracer_sim::SimNode>(ros::NodeHandle(), ros::NodeHandle("~"));
  } catch (const std::exception& e) {
    ROS_FATAL("tianracer_sim: %s", e.what());
    return 1;
  }
  node->run();
  return 0;
}
