// Every sensor kind has exactly one publisher: both register beside their code
// (TIANRACER_SENSOR_KIND, TIANRACER_SENSOR_PUBLISHER), and the node checks them at start.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/ros/plugins/sensor_publisher.h"
#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {
namespace {

TEST(RosSensorPublishers, EveryKindHasOnePublisher) {
  EXPECT_EQ(sensorKinds().size(), 15u);
  for (const std::string& p : sensorPublisherProblems(sensorKinds())) ADD_FAILURE() << p;
  EXPECT_NO_THROW(checkSensorPublishers());
}

std::unique_ptr<SensorListener> noPublisher(SimSensor&, const PublisherSetup&) { return nullptr; }

TEST(RosSensorPublishers, AKindWithoutOrWithTwoPublishersIsNamed) {
  std::vector<SensorKind> kinds = sensorKinds();
  SensorKind orphan = kinds.front();
  orphan.id = "test_orphan";
  kinds.push_back(orphan);
  SensorKind twice = kinds.front();
  twice.id = "test_twice";
  kinds.push_back(twice);
  registerSensorPublisher("test_twice", &noPublisher);
  registerSensorPublisher("test_twice", &noPublisher);
  EXPECT_THAT(sensorPublisherProblems(kinds),
              ::testing::ElementsAre("sensor kind 'test_orphan' has no publisher registered",
                                     "sensor kind 'test_twice' has 2 publishers registered"));
}

}  // namespace
}  // namespace tianracer_sim
