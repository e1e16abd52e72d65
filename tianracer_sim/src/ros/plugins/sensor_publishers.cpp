// The registry of the sensor publishers: each registers beside its code
// (TIANRACER_SENSOR_PUBLISHER), by the id of its SensorKind.
#include <map>
#include <stdexcept>

#include "tianracer_sim/ros/plugins/sensor_publisher.h"
#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {
namespace {

std::multimap<std::string, SensorPublisherFactory>& factories() {
  static std::multimap<std::string, SensorPublisherFactory> registered;
  return registered;
}

}  // namespace

bool registerSensorPublisher(const std::string& kind, SensorPublisherFactory factory) {
  factories().emplace(kind, factory);
  return true;
}

std::vector<std::string> sensorPublisherProblems(const std::vector<SensorKind>& kinds) {
  std::vector<std::string> problems;
  for (const SensorKind& kind : kinds) {
    const size_t n = factories().count(kind.id);
    if (n == 0) problems.push_back("sensor kind '" + kind.id + "' has no publisher registered");
    if (n > 1) problems.push_back("sensor kind '" + kind.id + "' has " + std::to_string(n) + " publishers registered");
  }
  return problems;
}

void checkSensorPublishers() {
  const std::vector<std::string> problems = sensorPublisherProblems(sensorKinds());
  if (problems.empty()) return;
  std::string text = "the sensor kinds and their publishers disagree:";
  for (const std::string& p : problems) text += "\n  " + p;
  throw std::logic_error(text);
}

std::unique_ptr<SensorListener> makeSensorPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  const auto it = factories().find(sensor.kind());
  if (it == factories().end())
    throw std::logic_error("sensor kind '" + sensor.kind() + "' has no publisher registered");
  return it->second(sensor, setup);
}

}  // namespace tianracer_sim
