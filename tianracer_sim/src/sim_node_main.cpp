// tianracer_sim_node: the simulator. Configuration errors end it with exit code 1 and a
// message naming the parameter, file or controller.
#include <malloc.h>

#include <memory>
#include <string>
#include <vector>

#include <ros/master.h>
#include <ros/ros.h>

#include "tianracer_sim/ros/sim_node.h"

namespace {

// The node is the clock: it never reads ros::Time::now(). With /use_sim_time true roscpp
// would subscribe it to its own /clock, and every /clock message (200 per sim second, at
// 20x real time 4000 a second) would come back over TCP to be deserialised and thrown away:
// about a tenth of the node's CPU in the physics-only benchmark. Remapping the parameter's
// name for this process only keeps roscpp on wall time here; /use_sim_time itself is set
// for the other nodes below.
constexpr const char* kOwnClockRemap = "/use_sim_time:=/_tianracer_sim_node/wall_clock_only";

void setUseSimTimeForOthers() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = "/use_sim_time";  // not remapped: master::execute takes the name as is
  args[2] = true;
  if (!ros::master::execute("setParam", args, result, payload, true)) {
    ROS_WARN("tianracer_sim: could not set /use_sim_time on the master");
  }
}

// roscpp serialises every message into a fresh buffer (10 MB for the depth camera's cloud).
// glibc gives blocks that large their own mmap, or trims them off the heap when freed, so each
// publish page-faulted its buffer in anew: 8 % of the main thread with the seed sensors. Kept
// on the heap, the same memory is reused message after message (RSS stays flat).
void keepLargeBuffersOnTheHeap() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's maximum on 64-bit
  mallopt(M_TRIM_THRESHOLD, 128 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  keepLargeBuffersOnTheHeap();
  std::vector<char*> args(argv, argv + argc);
  std::string remap = kOwnClockRemap;
  args.push_back(remap.data());
  int n = static_cast<int>(args.size());
  ros::init(n, args.data(), "tianracer_sim");
  // Held for the whole run: when a failed SimNode drops the last NodeHandle, roscpp shuts
  // down and the error below would never be printed.
  ros::NodeHandle keep_alive;
  setUseSimTimeForOthers();
  std::unique_ptr<tianracer_sim::SimNode> node;
  try {
    const ros::NodeHandle pnh("~");
    node = std::make_unique<tianracer_sim::SimNode>(ros::NodeHandle(), pnh,
                                                    tianracer_sim::makeSimNodeCore(pnh));
  } catch (const std::exception& e) {
    ROS_FATAL("tianracer_sim: %s", e.what());
    return 1;
  }
  node->run();
  return 0;
}
