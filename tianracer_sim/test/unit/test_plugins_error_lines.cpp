// A <sensor>'s errors name the line of the bad element itself, not the <sensor>'s, for each
// sensor kind family (ray, camera, IMU) and from both a robot URDF's <gazebo><sensor> and a
// world SDF's link; and the sensor's own SDF values keep their defaults when empty.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/plugins/camera/camera_config.h"
#include "tianracer_sim/plugins/imu/imu_sensor.h"
#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/world/world.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

// A robot with one link 'l' whose <gazebo> holds `sensor`, which starts on line 4.
std::string robot(const std::string& sensor) {
  return "<robot name='r'>\n"        // 1
         "  <link name='l'/>\n"      // 2
         "  <gazebo reference='l'>\n"  // 3
         + sensor +                  // 4...
         "\n  </gazebo>\n</robot>\n";
}

SensorSpec robotSensor(const std::string& sensor) {
  const RobotExtensions ext = parseExtensions(robot(sensor), "robot.urdf", {});
  return ext.links.at("l").sensors.at(0);
}

// A world with one model whose link 'l' holds `sensor`, which starts on line 4.
SensorSpec worldSensor(const std::string& sensor) {
  const WorldDescription w = loadWorldString(
      "<sdf version='1.6'><world name='w'>\n"  // 1
      "<model name='m'>\n"                     // 2
      "<link name='l'>\n"                      // 3
      + sensor +                               // 4...
      "\n</link></model></world></sdf>\n",
      "room.world", ".");
  return w.models.at(0).links.at(0).sensors.at(0);
}

template <class F>
std::string errorOf(F f) {
  return test::errorText<InputError>(f, "(no error)");
}

const char* kRay =
    "<sensor type='ray' name='laser'>\n"        // 4
    "  <ray>\n"                                 // 5
    "    <scan><horizontal>\n"                  // 6
    "      <samples>many</samples>\n"           // 7
    "    </horizontal></scan>\n"                // 8
    "    <range><min>0.1</min><max>5</max></range>\n"  // 9
    "  </ray>\n"                                // 10
    "</sensor>";

TEST(SensorErrorLines, RayFromARobotAndFromAWorld) {
  for (const auto& [spec, file] : {std::pair{robotSensor(kRay), std::string("robot.urdf")},
                                   std::pair{worldSensor(kRay), std::string("room.world")}}) {
    EXPECT_EQ(spec.line, 4);
    const std::string e = errorOf([&, &s = spec] { parseRaySensorConfig(s); });
    EXPECT_NE(e.find(file + ":7: sensor 'laser': <samples> 'many' is not an integer"),
              std::string::npos)
        << e;
  }
}

// The checks after reading (validate()) are placed at the element they name too.
TEST(SensorErrorLines, RayChecksAfterReading) {
  std::string xml = kRay;
  xml.replace(xml.find("many"), 4, "0");
  EXPECT_EQ(errorOf([&] { parseRaySensorConfig(robotSensor(xml)); }),
            "robot.urdf:7: sensor 'laser': <samples> must be > 0 (got 0)");
  xml.replace(xml.find("<samples>0"), 10, "<samples>10");
  xml.replace(xml.find("<min>0.1"), 8, "<min>6");
  EXPECT_EQ(errorOf([&] { parseRaySensorConfig(worldSensor(xml)); }),
            "room.world:9: sensor 'laser': range <min> 6 must be < range <max> 5");
}

const char* kCamera =
    "<sensor type='camera' name='cam'>\n"        // 4
    "  <camera>\n"                               // 5
    "    <horizontal_fov>1.0</horizontal_fov>\n"  // 6
    "    <image>\n"                              // 7
    "      <width>640</width>\n"                 // 8
    "      <height>ten</height>\n"               // 9
    "    </image>\n"                             // 10
    "    <clip><near>0.1</near><far>100</far></clip>\n"  // 11
    "  </camera>\n"                              // 12
    "</sensor>";

TEST(SensorErrorLines, CameraValuesAndItsChecksAfterReading) {
  for (const SensorSpec& spec : {robotSensor(kCamera), worldSensor(kCamera)}) {
    const std::string e = errorOf([&] { parseCameraConfig(spec); });
    EXPECT_NE(e.find(":9: camera sensor 'cam' on link 'l': <image><height> 'ten' is not a number"),
              std::string::npos)
        << e;
  }
  // A value that reads but is checked afterwards is still placed at its own element.
  std::string xml = kCamera;
  xml.replace(xml.find("ten"), 3, "480");
  xml.replace(xml.find("<near>0.1"), 9, "<near>-1");
  const std::string e = errorOf([&] { parseCameraConfig(robotSensor(xml)); });
  EXPECT_NE(e.find("robot.urdf:11: camera sensor 'cam' on link 'l': <clip><near> -1 must be > 0"),
            std::string::npos)
      << e;
  xml.replace(xml.find("<near>-1"), 8, "<near>0.1");
  xml.replace(xml.find("1.0</horizontal_fov>"), 3, "9.0");
  const std::string fov = errorOf([&] { parseCameraConfig(worldSensor(xml)); });
  EXPECT_NE(fov.find("room.world:6: camera sensor 'cam' on link 'l': <horizontal_fov> 9 rad"),
            std::string::npos)
      << fov;
}

const char* kImu =
    "<sensor type='imu' name='imu'>\n"             // 4
    "  <update_rate></update_rate>\n"              // 5
    "  <pose/>\n"                                  // 6
    "  <imu><angular_velocity><x><noise type='gaussian'>\n"  // 7
    "    <stddev>lots</stddev>\n"                  // 8
    "  </noise></x></angular_velocity></imu>\n"    // 9
    "</sensor>";

TEST(SensorErrorLines, ImuFromARobotAndFromAWorld) {
  for (const auto& [spec, file] : {std::pair{robotSensor(kImu), std::string("robot.urdf")},
                                   std::pair{worldSensor(kImu), std::string("room.world")}}) {
    EXPECT_TRUE(spec.error.empty()) << spec.error;  // empty <update_rate> and <pose> are fine
    const std::string e = errorOf([&, &s = spec] { parseImuSensorConfig(s, "m"); });
    EXPECT_NE(e.find(file + ":8: IMU sensor 'imu' on link 'l' of model 'm': <stddev> 'lots' is "
                            "not a number"),
              std::string::npos)
        << e;
  }
}

// sdformat keeps an empty element's default: <update_rate/> is 0 (every step), <pose/> the
// identity; a wrong value is still an error, placed at its line.
TEST(SensorErrorLines, EmptySensorValuesKeepTheirDefaults) {
  std::string xml = kImu;
  xml.replace(xml.find("lots"), 4, "0.01");
  const SensorSpec spec = robotSensor(xml);
  EXPECT_TRUE(spec.error.empty()) << spec.error;
  EXPECT_EQ(spec.update_rate, 0.0);
  EXPECT_TRUE(spec.X_LS.isApprox(Eigen::Isometry3d::Identity()));
  const ImuConfig c = parseImuSensorConfig(spec, "m");
  EXPECT_EQ(c.update_rate, 0.0);
  EXPECT_DOUBLE_EQ(c.rate_noise[0].stddev, 0.01);
  xml.replace(xml.find("<pose/>"), 7, "<pose>1 2</pose>");
  EXPECT_NE(robotSensor(xml).error.find("robot.urdf:6: sensor 'imu' on link 'l': <pose> '1 2' is "
                                        "not 6 numbers"),
            std::string::npos)
      << robotSensor(xml).error;
}

}  // namespace
}  // namespace tianracer_sim
