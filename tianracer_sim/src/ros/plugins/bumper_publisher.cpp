// libgazebo_ros_bumper on a contact sensor: the link's contacts as gazebo_msgs/ContactsState
// (see plugins/bumper/bumper.h), published at the sensor's rate, empty when nothing touches.
#include <gazebo_msgs/ContactsState.h>

#include "factories.h"
#include "tianracer_sim/ros/bumper_msgs.h"
#include "topic_publisher.h"

namespace tianracer_sim {
namespace {

void toMsg(const SimBumper& sensor, const ros::Time& stamp, gazebo_msgs::ContactsState* msg) {
  toContactsState(sensor.states(), stamp, sensor.frame(), msg);
}

}  // namespace

std::unique_ptr<SensorListener> makeBumperPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  return makeLinkSensorPublisher<SimBumper, gazebo_msgs::ContactsState>(
      sensor, setup, "contact sensor", "contact sensor '%s': link %s, frame %s, %g Hz on %s",
      &toMsg);
}

TIANRACER_SENSOR_PUBLISHER(bumperKind, makeBumperPublisher);

}  // namespace tianracer_sim
