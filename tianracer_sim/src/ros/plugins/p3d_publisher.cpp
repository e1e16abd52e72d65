// libgazebo_ros_p3d: a link's ground truth as nav_msgs/Odometry (see plugins/p3d/p3d.h).
#include <nav_msgs/Odometry.h>

#include "factories.h"
#include "tianracer_sim/ros/state_msgs.h"
#include "topic_publisher.h"

namespace tianracer_sim {
namespace {

void toMsg(const SimP3d& sensor, const ros::Time& stamp, nav_msgs::Odometry* msg) {
  toOdometry(sensor.reading(), stamp, sensor.frame(), sensor.childFrame(), msg);
}

}  // namespace

std::unique_ptr<SensorListener> makeP3dPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return makeLinkSensorPublisher<SimP3d, nav_msgs::Odometry>(
      sensor, setup, "p3d", "p3d '%s': link %s in %s, %g Hz on %s", &toMsg);
}

TIANRACER_SENSOR_PUBLISHER(p3dKind, makeP3dPublisher);

}  // namespace tianracer_sim
