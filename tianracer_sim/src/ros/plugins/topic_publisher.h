// The publisher of a sensor that sends one message type on one topic (bumper, p3d, IMU, lidar,
// range, block laser): the scaffolding each gazebo_ros sensor plugin repeats (claim the topic,
// advertise it, publish only while someone subscribes), written once. A sensor's file gives
// what is its own: its message, topic, queue and conversion, and the line it logs.
#ifndef TIANRACER_SIM_SRC_ROS_SENSORS_TOPIC_PUBLISHER_H
#define TIANRACER_SIM_SRC_ROS_SENSORS_TOPIC_PUBLISHER_H

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "tianracer_sim/ros/plugins/sensor_publisher.h"

namespace tianracer_sim {

/// Where and how a TopicPublisher publishes.
struct TopicSpec {
  std::string topic;
  std::string what;  // the sensor in messages, e.g. "p3d 'name'" (after setup.owner())
  uint32_t queue_size = 10;
  /// Times the conversion and the send in the step profile's rows
  /// "sensor <kind>: publish / convert" and ".../ serialise and send".
  bool profile_parts = false;
};

/// Claims spec.topic for the sensor (throws when another sensor publishes it), advertises it,
/// names the sensor's stat after it; wants the due outputs only while the topic has a
/// subscriber, and publishes each one as convert(sensor, stamp, &msg) fills it.
template <class Sensor, class Msg>
class TopicPublisher : public SensorListener {
 public:
  using Convert = void (*)(const Sensor& sensor, const ros::Time& stamp, Msg* msg);

  TopicPublisher(Sensor& sensor, const PublisherSetup& setup, const TopicSpec& spec,
                 Convert convert)
      : convert_(convert) {
    setup.claim_topic(spec.topic, setup.owner() + " " + spec.what);
    ros::NodeHandle root = setup.root;
    pub_ = root.advertise<Msg>(spec.topic, spec.queue_size);
    sensor.stat().name = spec.topic;
    if (spec.profile_parts) {
      profile_ = setup.profile;
      const std::string row = "sensor " + sensor.kind() + ": publish / ";
      convert_row_ = profileRow(profile_, row + "convert");
      send_row_ = profileRow(profile_, row + "serialise and send");
    }
  }

  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override {
    return pub_.getNumSubscribers() > 0 ? due : 0;
  }

  void onOutputs(const SimSensor& sensor, SensorOutputs, double t) override {
    std::optional<StepProfile::Scope> part(std::in_place, profile_, convert_row_);
    convert_(static_cast<const Sensor&>(sensor), ros::Time(t), &msg_);
    part.emplace(profile_, send_row_);
    pub_.publish(msg_);
  }

 protected:
  Msg msg_;  // kept between publications: no allocation once warm

 private:
  Convert convert_;
  ros::Publisher pub_;
  StepProfile* profile_ = nullptr;
  int convert_row_ = -1, send_row_ = -1;
};

/// The publisher of a sensor on a link that reports in a frame (bumper, p3d): its config's
/// topic(), name, link and update_rate, and the sensor's frame(), logged as `log_format` gives
/// them (name, link, frame, rate, topic). `label` names the sensor kind in messages.
template <class Sensor, class Msg>
std::unique_ptr<SensorListener> makeLinkSensorPublisher(
    SimSensor& s, const PublisherSetup& setup, const std::string& label, const char* log_format,
    typename TopicPublisher<Sensor, Msg>::Convert convert) {
  auto& sensor = static_cast<Sensor&>(s);
  const auto& c = sensor.config();
  auto publisher = std::make_unique<TopicPublisher<Sensor, Msg>>(
      sensor, setup, TopicSpec{c.topic(), label + " '" + c.name + "'", 10}, convert);
  ROS_INFO(log_format, c.name.c_str(), c.link.c_str(), sensor.frame().c_str(), c.update_rate,
           c.topic().c_str());
  return publisher;
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SRC_ROS_SENSORS_TOPIC_PUBLISHER_H
