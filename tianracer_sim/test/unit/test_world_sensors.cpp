// <sensor> in a world model's <link>: parsed into the SensorSpec robots' sensors take (with its
// plugins, pose and rate), named after the link (nested models' links as "<sub>::<link>"); a
// sensor that cannot be used is an error that leaves it out, and the world loads.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

std::string world(const std::string& models) {
  return "<sdf version='1.6'><world name='w'>" + models + "</world></sdf>";
}

const std::string kLidar =
    "<sensor type='ray' name='lidar'><pose>0.1 0 0.2 0 0 1.5707963</pose>"
    "<update_rate>25</update_rate><always_on>false</always_on>"
    "<ray><scan><horizontal><samples>10</samples><min_angle>-1</min_angle><max_angle>1</max_angle>"
    "</horizontal></scan><range><min>0.1</min><max>5</max></range></ray>"
    "<plugin name='laser' filename='libgazebo_ros_laser.so'><topicName>scan</topicName>"
    "<frameName>lidar_frame</frameName></plugin></sensor>";

const SensorSpec* sensorOf(const WorldDescription& w, const std::string& model,
                           const std::string& link, const std::string& name) {
  for (const ModelDescription& m : w.models) {
    if (m.name != model) continue;
    for (const LinkDescription& l : m.links) {
      if (l.name != link) continue;
      for (const SensorSpec& s : l.sensors) {
        if (s.name == name) return &s;
      }
    }
  }
  return nullptr;
}

TEST(WorldSensors, ALinksSensorIsParsedAsARobotsIs) {
  std::vector<std::string> warnings;
  WorldLoadOptions o;
  o.warn = [&](const std::string& w) { warnings.push_back(w); };
  const WorldDescription w = loadWorldString(
      world("<model name='post'><static>true</static><link name='head'>" + kLidar +
            "</link></model>"),
      "inline.world", ".", o);
  const SensorSpec* s = sensorOf(w, "post", "head", "lidar");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->type, "ray");
  EXPECT_EQ(s->link, "head");
  EXPECT_DOUBLE_EQ(s->update_rate, 25.0);
  EXPECT_FALSE(s->always_on);
  EXPECT_TRUE(s->X_LS.translation().isApprox(Eigen::Vector3d(0.1, 0, 0.2)));
  EXPECT_TRUE((s->X_LS.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-6));
  ASSERT_EQ(s->plugins.size(), 1u);
  EXPECT_EQ(s->plugins[0].filename, "libgazebo_ros_laser.so");
  EXPECT_EQ(s->plugins[0].params.at("topicName"), "scan");
  EXPECT_EQ(s->source, "inline.world");
  EXPECT_EQ(s->line, 1);
  EXPECT_NE(s->xml.find("<horizontal>"), std::string::npos);
  EXPECT_TRUE(s->error.empty());
  // The sensor is no unsupported element of the link any more.
  for (const std::string& warning : warnings) EXPECT_EQ(warning.find("sensor"), std::string::npos) << warning;
}

TEST(WorldSensors, ANestedModelsSensorIsOnTheMergedLink) {
  const WorldDescription w = loadWorldString(
      world("<model name='outer'><link name='base'/><model name='inner'><link name='head'>" +
            kLidar + "</link></model></model>"),
      "inline.world", ".");
  const SensorSpec* s = sensorOf(w, "outer", "inner::head", "lidar");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->link, "inner::head");
}

TEST(WorldSensors, ABadSensorIsLeftOutWithAnErrorAndTheWorldLoads) {
  std::vector<std::string> errors;
  WorldLoadOptions o;
  o.error = [&](const std::string& e) { errors.push_back(e); };
  const std::string xml = world(
      "<model name='post'><static>true</static><link name='head'>\n"
      "<sensor type='ray'><update_rate>5</update_rate></sensor>\n" + kLidar +
      "\n<sensor name='nameless_plugin' type='camera'><plugin name='p'/></sensor>"
      "</link></model>");
  const WorldDescription w = loadWorldString(xml, "inline.world", ".", o);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NE(errors[0].find("inline.world:2: sensor on link 'head' has no name"), std::string::npos)
      << errors[0];
  EXPECT_NE(errors[0].find("the sensor is left out"), std::string::npos) << errors[0];
  EXPECT_NE(errors[1].find("inline.world:4: plugin 'p' has no filename"), std::string::npos)
      << errors[1];
  ASSERT_EQ(w.models.size(), 1u);
  ASSERT_EQ(w.models[0].links.size(), 1u);
  ASSERT_EQ(w.models[0].links[0].sensors.size(), 1u);
  EXPECT_EQ(w.models[0].links[0].sensors[0].name, "lidar");

  // A bad value of the sensor's own tags is kept with the sensor (the Simulator leaves it out
  // with the message, as for a robot).
  const WorldDescription bad = loadWorldString(
      world("<model name='post'><link name='head'><sensor name='s' type='ray'>"
            "<update_rate>-1</update_rate></sensor></link></model>"),
      "inline.world", ".");
  const SensorSpec* s = sensorOf(bad, "post", "head", "s");
  ASSERT_NE(s, nullptr);
  EXPECT_NE(s->error.find("<update_rate> value '-1'"), std::string::npos) << s->error;

  // ~strict_world stops at the first.
  WorldLoadOptions strict;
  strict.strict = true;
  EXPECT_THROW(loadWorldString(xml, "inline.world", ".", strict), WorldError);
}

}  // namespace
}  // namespace tianracer_sim
