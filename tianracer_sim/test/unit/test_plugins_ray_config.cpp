// <sensor type="ray"> -> RaySensorConfig: the seed's hokuyo, plugin defaults, and every bad value.
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/plugins/ray/ray_sensor.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

using test::replaced;

// The seed's block (tianracer.gazebo), as the model loader hands it over.
const char* kSeedSensor = R"(<sensor type="ray" name="hokuyo_sensor">
  <pose>0 0 0.0124 0 0 0</pose>
  <visualize>false</visualize>
  <update_rate>40</update_rate>
  <ray>
    <scan>
      <horizontal>
        <samples>1081</samples>
        <resolution>1</resolution>
        <min_angle>-2.3561944902</min_angle>
        <max_angle>2.3561944902</max_angle>
      </horizontal>
    </scan>
    <range>
      <min>0.1</min>
      <max>10.0</max>
      <resolution>0.01</resolution>
    </range>
    <noise>
      <mean>0.0</mean>
      <stddev>0.01</stddev>
    </noise>
  </ray>
  <plugin name="gazebo_ros_hokuyo_controller" filename="libgazebo_ros_laser.so">
    <topicName>/scan</topicName>
    <frameName>lidar</frameName>
  </plugin>
</sensor>)";

SensorSpec spec(const std::string& xml, bool with_plugin = true) {
  SensorSpec s;
  s.name = "hokuyo_sensor";
  s.type = "ray";
  s.link = "lidar";
  s.X_LS.translation().z() = 0.0124;
  s.update_rate = 40;
  s.xml = xml;
  s.source = "test.urdf";  // where the <sensor> stands: the place of the reader's messages
  s.line = 12;
  if (with_plugin) {
    PluginSpec p;
    p.name = "gazebo_ros_hokuyo_controller";
    p.filename = "libgazebo_ros_laser.so";
    p.params = {{"topicName", "/scan"}, {"frameName", "lidar"}};
    s.plugins.push_back(p);
  }
  return s;
}

std::string errorOf(const SensorSpec& s) {
  return test::errorText<SensorError>([&] { parseRaySensorConfig(s); }, "(no error)");
}

TEST(RaySensorConfig, SeedHokuyo) {
  std::vector<std::string> warnings;
  const RaySensorConfig c =
      parseRaySensorConfig(spec(kSeedSensor), [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
  EXPECT_EQ(c.name, "hokuyo_sensor");
  EXPECT_EQ(c.link, "lidar");
  EXPECT_DOUBLE_EQ(c.X_LS.translation().z(), 0.0124);
  EXPECT_DOUBLE_EQ(c.update_rate, 40);
  EXPECT_EQ(c.samples, 1081);
  EXPECT_DOUBLE_EQ(c.resolution, 1);
  EXPECT_DOUBLE_EQ(c.min_angle, -2.3561944902);
  EXPECT_DOUBLE_EQ(c.max_angle, 2.3561944902);
  EXPECT_NEAR(c.angleIncrement(), 0.0043633, 1e-7);
  EXPECT_DOUBLE_EQ(c.angle(1080), c.min_angle + 1080 * c.angleIncrement());
  EXPECT_DOUBLE_EQ(c.range_min, 0.1);
  EXPECT_DOUBLE_EQ(c.range_max, 10.0);
  EXPECT_DOUBLE_EQ(c.range_resolution, 0.01);
  EXPECT_EQ(c.noise.type, "gaussian");  // SDF's default when <type> is absent
  EXPECT_TRUE(c.noise.enabled());
  EXPECT_DOUBLE_EQ(c.noise.mean, 0.0);
  EXPECT_DOUBLE_EQ(c.noise.stddev, 0.01);
  EXPECT_TRUE(c.has_ros_plugin);
  EXPECT_EQ(c.topic_name, "/scan");
  EXPECT_EQ(c.frame_name, "lidar");
  EXPECT_EQ(c.robot_namespace, "");
}

TEST(RaySensorConfig, PluginDefaultsAndWarnings) {
  SensorSpec s = spec(replaced(kSeedSensor, "<visualize>false</visualize>",
                               "<visualize>false</visualize><topic>x</topic>"),
                      false);
  PluginSpec p;
  p.filename = "libgazebo_ros_laser.so";
  p.params = {{"robotNamespace", "/tianracer_02"}, {"gaussianNoise", "0.1"}};
  s.plugins.push_back(p);
  PluginSpec other;
  other.filename = "libmy_plugin.so";
  s.plugins.push_back(other);
  std::vector<std::string> warnings;
  const RaySensorConfig c =
      parseRaySensorConfig(s, [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_EQ(c.topic_name, "/world");    // gazebo_ros_laser's default
  EXPECT_EQ(c.frame_name, "lidar");     // ours: the link, not "/world"
  EXPECT_EQ(c.robot_namespace, "/tianracer_02");
  ASSERT_EQ(warnings.size(), 3u) << ::testing::PrintToString(warnings);
  EXPECT_NE(warnings[0].find("<topic> in <sensor> is not supported"), std::string::npos);
  EXPECT_NE(warnings[1].find("<gaussianNoise>"), std::string::npos);
  EXPECT_NE(warnings[2].find("libmy_plugin.so"), std::string::npos);

  // No plugin: a sensor without a ROS interface (Gazebo would publish nothing).
  const RaySensorConfig bare = parseRaySensorConfig(spec(kSeedSensor, false));
  EXPECT_FALSE(bare.has_ros_plugin);
  // No <noise>: noise off.
  const std::string quiet = replaced(kSeedSensor,
      "<noise>\n      <mean>0.0</mean>\n      <stddev>0.01</stddev>\n    </noise>", "");
  EXPECT_FALSE(parseRaySensorConfig(spec(quiet)).noise.enabled());
  // A frame with a leading slash loses it (tf2).
  SensorSpec slash = spec(kSeedSensor);
  slash.plugins[0].params["frameName"] = "/laser";
  EXPECT_EQ(parseRaySensorConfig(slash).frame_name, "laser");
}

// This spec has no line map (a copy made by hand): every place is the <sensor>'s line, 12.
TEST(RaySensorConfig, BadValuesNameSensorAndValue) {
  const std::string seed = kSeedSensor;
  auto with = [&](const std::string& from, const std::string& to) {
    return errorOf(spec(replaced(seed, from, to)));
  };
  EXPECT_EQ(with("<samples>1081</samples>", "<samples>0</samples>"),
            "test.urdf:12: sensor 'hokuyo_sensor': <samples> must be > 0 (got 0)");
  EXPECT_EQ(with("<samples>1081</samples>", "<samples>-5</samples>"),
            "test.urdf:12: sensor 'hokuyo_sensor': <samples> must be > 0 (got -5)");
  // Resource limit (issue 43): 1e9 samples allocated 4 GB and hung.
  EXPECT_EQ(with("<samples>1081</samples>", "<samples>1000000000</samples>"),
            "test.urdf:12: sensor 'hokuyo_sensor': <samples> 1000000000 x <vertical><samples> 1 rays per scan "
            "is out of range (<= 1e+06)");
  EXPECT_EQ(with("<samples>1081</samples>", "<samples>1000000</samples>"), "(no error)");  // at the limit
  EXPECT_NE(with("<samples>1081</samples>", "<samples>many</samples>")
                .find("test.urdf:12: sensor 'hokuyo_sensor': <samples> 'many' is not an integer"),
            std::string::npos);
  EXPECT_EQ(with("<min_angle>-2.3561944902</min_angle>", "<min_angle>3</min_angle>"),
            "test.urdf:12: sensor 'hokuyo_sensor': <min_angle> 3 > <max_angle> 2.35619449");
  EXPECT_EQ(with("<min>0.1</min>", "<min>10</min>"),
            "test.urdf:12: sensor 'hokuyo_sensor': range <min> 10 must be < range <max> 10");
  EXPECT_EQ(with("<min>0.1</min>", "<min>12</min>"),
            "test.urdf:12: sensor 'hokuyo_sensor': range <min> 12 must be < range <max> 10");
  EXPECT_EQ(with("<min>0.1</min>", "<min>-1</min>"),
            "test.urdf:12: sensor 'hokuyo_sensor': range <min> must be >= 0 (got -1)");
  // An element edited from -> to, and what the error says.
  const std::tuple<const char*, const char*, const char*> edits[] = {
      {"<max>10.0</max>", "<max>inf</max>", "<max> 'inf' is not a finite number"},
      {"<max_angle>2.3561944902</max_angle>", "<max_angle>nan</max_angle>",
       "<max_angle> 'nan' is not a finite number"},
      {"<stddev>0.01</stddev>", "<stddev>-0.01</stddev>", "noise <stddev> must be >= 0"},
      {"<mean>0.0</mean>", "<type>uniform</type><mean>0.0</mean>",
       "noise <type> 'uniform' is not supported"},
      {"<resolution>1</resolution>", "<resolution>0</resolution>",
       "<horizontal><resolution> must be > 0"}};
  for (const auto& [from, to, message] : edits) {
    EXPECT_NE(with(from, to).find(message), std::string::npos) << to;
  }
  EXPECT_NE(errorOf(spec("<sensor name='x'><ray>")).find("its XML does not parse"),
            std::string::npos);
  EXPECT_NE(errorOf(spec("<sensor name='x'/>")).find("no <ray> element"), std::string::npos);
  SensorSpec camera = spec(kSeedSensor);
  camera.type = "camera";
  EXPECT_NE(errorOf(camera).find("type 'camera' is not a ray sensor"), std::string::npos);
}

TEST(RaySensorConfig, ValidateCatchesProgrammaticValues) {
  RaySensorConfig c = parseRaySensorConfig(spec(kSeedSensor));
  c.update_rate = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate(c), SensorError);
  c.update_rate = -1;
  EXPECT_THROW(validate(c), SensorError);
  c.update_rate = 40;
  c.X_LS.translation().x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(validate(c), SensorError);
  c.X_LS.translation().x() = 0;
  EXPECT_NO_THROW(validate(c));
  c.samples = 0;
  EXPECT_THROW(RaySensor{c}, SensorError);
  c.samples = 1;  // a single beam is valid: increment 0
  c.min_angle = c.max_angle = 0.0;
  EXPECT_NO_THROW(validate(c));
  EXPECT_DOUBLE_EQ(c.angleIncrement(), 0.0);
}

TEST(RaySensorConfig, VerticalSamplesMakeA3dLidar) {
  std::vector<std::string> warnings;
  const auto warn = [&](const std::string& w) { warnings.push_back(w); };
  const std::string xml = replaced(kSeedSensor, "</horizontal>",
                                   "</horizontal><vertical><samples>16</samples>"
                                   "<min_angle>-0.2</min_angle><max_angle>0.25</max_angle></vertical>");
  const RaySensorConfig c = parseRaySensorConfig(spec(xml), warn);
  EXPECT_TRUE(warnings.empty()) << ::testing::PrintToString(warnings);
  EXPECT_EQ(c.vertical_samples, 16);
  EXPECT_DOUBLE_EQ(c.verticalAngle(0), -0.2);
  EXPECT_DOUBLE_EQ(c.verticalAngle(15), 0.25);
  EXPECT_EQ(c.rayCount(), 16 * 1081);
  // A planar scan with vertical angles: they are ignored, with a warning.
  parseRaySensorConfig(spec(replaced(kSeedSensor, "</horizontal>",
                                     "</horizontal><vertical><samples>1</samples>"
                                     "<min_angle>-0.2</min_angle></vertical>")),
                       warn);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("planar scan"), std::string::npos);
  // Bad input: 0 or more than 512 rings, min above max.
  for (const std::string& bad : {std::string("0"), std::string("513"), std::string("-3")}) {
    try {
      parseRaySensorConfig(spec(replaced(kSeedSensor, "</horizontal>",
                                         "</horizontal><vertical><samples>" + bad +
                                             "</samples></vertical>")));
      ADD_FAILURE() << bad;
    } catch (const SensorError& e) {
      EXPECT_NE(std::string(e.what()).find("<vertical><samples> " + bad + " out of range 1..512"),
                std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("hokuyo_sensor"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parseRaySensorConfig(spec(replaced(
                   kSeedSensor, "</horizontal>",
                   "</horizontal><vertical><samples>4</samples><min_angle>0.3</min_angle>"
                   "<max_angle>0.1</max_angle></vertical>"))),
               SensorError);
}

TEST(RaySensorConfig, VelodynePlugin) {
  const std::string xml = replaced(kSeedSensor, "</horizontal>",
                                   "</horizontal><vertical><samples>16</samples><min_angle>-0.26"
                                   "</min_angle><max_angle>0.26</max_angle></vertical>");
  SensorSpec s = spec(xml, false);
  PluginSpec p;
  p.name = "v";
  p.filename = "libgazebo_ros_velodyne_gpu_laser.so";
  p.params = {{"topicName", "/velodyne_points"}, {"frameName", "velodyne"}, {"min_range", "0.9"},
              {"max_range", "130"}, {"gaussianNoise", "0.008"}};
  s.plugins.push_back(p);
  const RaySensorConfig c = parseRaySensorConfig(s);
  EXPECT_TRUE(c.velodyne);
  EXPECT_EQ(c.topic_name, "/velodyne_points");
  EXPECT_EQ(c.frame_name, "velodyne");
  EXPECT_DOUBLE_EQ(c.cloud_min_range, 0.9);
  EXPECT_DOUBLE_EQ(c.cloud_max_range, 130.0);
  EXPECT_DOUBLE_EQ(c.cloud_noise, 0.008);
  const auto topics = publishedTopics(c);
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].msg_type, "sensor_msgs/PointCloud2");
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

namespace tianracer_sim {
namespace {

// A <sensor> is kept as a printed copy; its parser still places an error at the bad element's
// own line in the model file (SensorSpec::xml_lines), not at the <sensor> line.
TEST(RaySensorConfig, ErrorsNameTheLineOfTheBadElement) {
  const std::string urdf =
      "<robot name='r'>\n"                                           // 1
      "  <link name='lidar'/>\n"                                     // 2
      "  <gazebo reference='lidar'>\n"                               // 3
      "    <sensor type='ray' name='laser'>\n"                       // 4
      "      <ray>\n"                                                // 5
      "        <scan><horizontal>\n"                                 // 6
      "          <samples>many</samples>\n"                          // 7
      "        </horizontal></scan>\n"                               // 8
      "        <range><min>0.1</min><max>5</max></range>\n"          // 9
      "      </ray>\n"                                               // 10
      "    </sensor>\n"                                              // 11
      "  </gazebo>\n"                                                // 12
      "</robot>\n";
  const RobotExtensions ext = parseExtensions(urdf, "robot.urdf", {});
  const SensorSpec& s = ext.links.at("lidar").sensors.at(0);
  EXPECT_EQ(s.line, 4);
  const std::string error =
      test::errorText<SensorError>([&] { parseRaySensorConfig(s); }, "(no error)");
  EXPECT_NE(error.find("robot.urdf:7: sensor 'laser': <samples> 'many' is not an integer"),
            std::string::npos)
      << error;
  // A copy edited since it was printed (its elements no longer match the lines) falls back to
  // the <sensor>'s line rather than a wrong one.
  SensorSpec edited = s;
  edited.xml.replace(edited.xml.find("<ray>"), 5, "<ray><extra/>");
  const std::string fallback =
      test::errorText<SensorError>([&] { parseRaySensorConfig(edited); }, "(no error)");
  EXPECT_NE(fallback.find("robot.urdf:4: sensor 'laser': <samples>"), std::string::npos) << fallback;
}

}  // namespace
}  // namespace tianracer_sim
