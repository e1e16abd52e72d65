// The sensor registry: which kind simulates a <sensor>, and the topics it publishes are the
// ones the node advertises (model_info prints these).
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::ElementsAre;
using test::topicNames;

/// One link with the given <gazebo reference> body, parsed as the model loader does.
SensorSpec sensorFrom(const std::string& gazebo_body) {
  const std::string urdf =
      "<robot name='r'><link name='base'/>"
      "<gazebo reference='base'>" + gazebo_body + "</gazebo></robot>";
  const RobotExtensions ext = parseExtensions(urdf, "test.urdf", {});
  EXPECT_EQ(ext.links.count("base"), 1u);
  EXPECT_EQ(ext.links.at("base").sensors.size(), 1u);
  return ext.links.at("base").sensors.front();
}

const char* kCameraBody =
    "<camera><horizontal_fov>1.0</horizontal_fov><image><width>64</width><height>48</height>"
    "<format>R8G8B8</format></image><clip><near>0.1</near><far>10</far></clip></camera>";

std::string depthSensor(const std::string& plugin_file, const std::string& params) {
  return std::string("<sensor type='depth' name='rs'><update_rate>20</update_rate>") + kCameraBody +
         "<plugin name='p' filename='" + plugin_file + "'><cameraName>rs</cameraName>"
         "<updateRate>10</updateRate>" + params + "</plugin></sensor>";
}

TEST(SensorsRegistry, GazeboPluginsOfTheUpstreamSuite) {
  const std::string grid =
      "<ray><scan><horizontal><samples>5</samples><min_angle>-0.25</min_angle>"
      "<max_angle>0.25</max_angle></horizontal><vertical><samples>5</samples>"
      "<min_angle>-0.25</min_angle><max_angle>0.25</max_angle></vertical></scan>"
      "<range><min>0.01</min><max>0.75</max></range></ray>";
  const SensorSpec range = sensorFrom("<sensor type='ray' name='s'><update_rate>5</update_rate>" +
                                      grid + "<plugin name='p' filename='libgazebo_ros_range.so'>"
                                      "<topicName>sonar</topicName></plugin></sensor>");
  EXPECT_EQ(test::kindOf(range), "range");
  std::vector<SensorTopic> t = sensorTopics(range, "r");
  ASSERT_THAT(topicNames(t), ElementsAre("/sonar"));
  EXPECT_EQ(t[0].msg_type, "sensor_msgs/Range");
  const SensorSpec block = sensorFrom("<sensor type='ray' name='b'><update_rate>5</update_rate>" +
                                      grid + "<plugin name='p' filename='libgazebo_ros_block_laser.so'>"
                                      "<topicName>cloud</topicName></plugin></sensor>");
  EXPECT_EQ(test::kindOf(block), "block_laser");
  t = sensorTopics(block, "r");
  ASSERT_THAT(topicNames(t), ElementsAre("/cloud"));
  EXPECT_EQ(t[0].msg_type, "sensor_msgs/PointCloud");
  const SensorSpec trig = sensorFrom(std::string("<sensor type='camera' name='c'>") + kCameraBody +
                                     "<plugin name='p' filename='libgazebo_ros_triggered_camera.so'>"
                                     "<cameraName>camera1</cameraName></plugin></sensor>");
  EXPECT_EQ(test::kindOf(trig), "camera");
  t = sensorTopics(trig, "r");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].topic, "/camera1/image_raw");
  // An empty <robotNamespace/> is the model's name: gazebo_ros_camera_utils.cpp Load calls
  // GetRobotNamespace (gazebo_ros_utils.h). A missing one is the root (above).
  const SensorSpec empty_ns = sensorFrom(std::string("<sensor type='camera' name='c'>") +
                                         kCameraBody + "<plugin name='p' filename='libgazebo_ros_camera.so'>"
                                         "<robotNamespace></robotNamespace><cameraName>cam</cameraName>"
                                         "</plugin></sensor>");
  t = sensorTopics(empty_ns, "pioneer");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].topic, "/pioneer/cam/image_raw");
}

TEST(SensorsRegistry, EmptyRobotNamespaceIsTheModelsNameWhereGazeboRosSaysSo) {
  // GetRobotNamespace: gazebo_ros_camera_utils (camera, depth, multicamera), gazebo_ros_laser,
  // gazebo_ros_gpu_laser. "/" stays the root (tianracer.gazebo's default sensor namespace).
  const auto camera = [](const std::string& ns_element) {
    return sensorFrom(std::string("<sensor type='camera' name='c'>") + kCameraBody +
                      "<plugin name='p' filename='libgazebo_ros_camera.so'>" + ns_element +
                      "<cameraName>rrbot/camera1</cameraName></plugin></sensor>");
  };
  EXPECT_EQ(sensorTopics(camera("<robotNamespace/>"), "tianracer")[0].topic,
            "/tianracer/rrbot/camera1/image_raw");
  EXPECT_EQ(sensorTopics(camera("<robotNamespace> </robotNamespace>"), "tianracer")[0].topic,
            "/tianracer/rrbot/camera1/image_raw");
  EXPECT_EQ(sensorTopics(camera("<robotNamespace>/</robotNamespace>"), "tianracer")[0].topic,
            "/rrbot/camera1/image_raw");
  EXPECT_EQ(sensorTopics(camera(""), "tianracer")[0].topic, "/rrbot/camera1/image_raw");

  const SensorSpec depth = sensorFrom(depthSensor("libgazebo_ros_openni_kinect.so",
                                                  "<robotNamespace/>"));
  EXPECT_EQ(sensorTopics(depth, "kinect_bot")[0].topic, "/kinect_bot/rs/ir/image_raw");

  const std::string ray_body =
      "<ray><scan><horizontal><samples>10</samples><min_angle>-1</min_angle>"
      "<max_angle>1</max_angle></horizontal></scan><range><min>0.1</min><max>5</max></range></ray>";
  const auto laser = [&](const std::string& file, const std::string& ns_element) {
    return sensorFrom("<sensor type='ray' name='l'>" + ray_body + "<plugin name='p' filename='" +
                      file + "'><topicName>scan</topicName>" + ns_element + "</plugin></sensor>");
  };
  EXPECT_THAT(topicNames(sensorTopics(laser("libgazebo_ros_laser.so", "<robotNamespace/>"), "car")),
              ElementsAre("/car/scan"));
  EXPECT_THAT(topicNames(sensorTopics(laser("libgazebo_ros_gpu_laser.so", "<robotNamespace/>"), "car")),
              ElementsAre("/car/scan"));
  EXPECT_THAT(topicNames(sensorTopics(laser("libgazebo_ros_laser.so", ""), "car")),
              ElementsAre("/scan"));
  // An absolute topicName stays where it is (the seed's /scan).
  const SensorSpec abs = sensorFrom("<sensor type='ray' name='l'>" + ray_body +
                                    "<plugin name='p' filename='libgazebo_ros_laser.so'>"
                                    "<topicName>/scan</topicName><robotNamespace/></plugin></sensor>");
  EXPECT_THAT(topicNames(sensorTopics(abs, "car")), ElementsAre("/scan"));
  // gazebo_ros_range reads robotNamespace itself ("" + "/"): the root, as upstream.
  const SensorSpec range = sensorFrom("<sensor type='ray' name='l'>" + ray_body +
                                      "<plugin name='p' filename='libgazebo_ros_range.so'>"
                                      "<topicName>sonar</topicName><robotNamespace/></plugin></sensor>");
  EXPECT_THAT(topicNames(sensorTopics(range, "car")), ElementsAre("/sonar"));
}

TEST(SensorsRegistry, KindsByTypeAndPlugin) {
  const std::string ray_body =
      "<ray><scan><horizontal><samples>10</samples><min_angle>-1</min_angle>"
      "<max_angle>1</max_angle></horizontal></scan><range><min>0.1</min><max>5</max></range></ray>";
  const SensorSpec ray = sensorFrom("<sensor type='ray' name='l'><update_rate>10</update_rate>" +
                                    ray_body +
                                    "<plugin name='p' filename='libgazebo_ros_laser.so'>"
                                    "<topicName>/scan</topicName></plugin></sensor>");
  EXPECT_EQ(test::kindOf(ray), "lidar");
  // gpu_ray with gazebo_ros_gpu_laser is simulated as ray.
  const SensorSpec gpu = sensorFrom("<sensor type='gpu_ray' name='l'>" + ray_body +
                                    "<plugin name='p' filename='libgazebo_ros_gpu_laser.so'>"
                                    "<topicName>scan</topicName><robotNamespace>car</robotNamespace>"
                                    "</plugin></sensor>");
  EXPECT_EQ(test::kindOf(gpu), "lidar");
  const std::vector<SensorTopic> t = sensorTopics(gpu, "r");
  ASSERT_THAT(topicNames(t), ElementsAre("/car/scan"));
  EXPECT_EQ(t[0].msg_type, "sensor_msgs/LaserScan");

  const SensorSpec unknown = sensorFrom("<sensor type='sonar' name='s'/>");
  EXPECT_EQ(findSensorKind(unknown), nullptr);
  EXPECT_TRUE(sensorTopics(unknown, "r").empty());
}

// The ray sensor's parser leaves the plugins other kinds of its type register to their own
// parsers (asked of the registry, not a list of its own), and warns about the rest.
TEST(SensorsRegistry, TheRaySensorAsksTheRegistryWhichPluginsAreOtherKinds) {
  ASSERT_NE(findPluginKind("ray", "/opt/lib/libgazebo_ros_range.so"), nullptr);
  EXPECT_EQ(findPluginKind("ray", "/opt/lib/libgazebo_ros_range.so")->id, "range");
  EXPECT_EQ(findPluginKind("gpu_ray", "libgazebo_ros_block_laser.so")->id, "block_laser");
  EXPECT_EQ(findPluginKind("ray", "libhector_gazebo_ros_sonar.so")->id, "hector_sonar");
  EXPECT_EQ(findPluginKind("camera", "libgazebo_ros_range.so"), nullptr);
  EXPECT_EQ(findPluginKind("ray", "libgazebo_ros_sonar_of_nobody.so"), nullptr);

  const std::string ray_body =
      "<ray><scan><horizontal><samples>10</samples><min_angle>-1</min_angle>"
      "<max_angle>1</max_angle></horizontal></scan><range><min>0.1</min><max>5</max></range></ray>";
  const auto warnings = [&](const std::string& file) {
    std::vector<std::string> out;
    parseRaySensorConfig(sensorFrom("<sensor type='ray' name='l'>" + ray_body +
                                    "<plugin name='p' filename='" + file + "'/></sensor>"),
                         [&out](const std::string& m) { out.push_back(m); });
    return out;
  };
  EXPECT_THAT(warnings("libgazebo_ros_range.so"), ::testing::IsEmpty());
  EXPECT_THAT(warnings("libgazebo_ros_block_laser.so"), ::testing::IsEmpty());
  EXPECT_THAT(warnings("libhector_gazebo_ros_sonar.so"), ::testing::IsEmpty());
  EXPECT_THAT(warnings("libgazebo_ros_sonar_of_nobody.so"),
              ElementsAre(::testing::HasSubstr(
                  "plugin 'libgazebo_ros_sonar_of_nobody.so' is not supported on a ray sensor")));
}

TEST(SensorsRegistry, EveryKindRegistersBesideItsClassAndTheyAgree) {
  std::vector<std::string> ids;
  for (const SensorKind& k : sensorKinds()) ids.push_back(k.id);
  // By id, whatever order the libraries registered them in.
  EXPECT_THAT(ids, ElementsAre("block_laser", "bumper", "camera", "depth_camera", "drive",
                               "hector_gps", "hector_imu", "hector_magnetic", "hector_sonar", "imu",
                               "imu_plugin", "lidar", "multicamera", "p3d", "range"));
  EXPECT_TRUE(sensorKindProblems(sensorKinds()).empty());
  // A ray sensor with no plugin of the four ray kinds is the type's default: a lidar.
  const SensorSpec bare = sensorFrom(
      "<sensor type='ray' name='l'><ray><scan><horizontal><samples>10</samples></horizontal>"
      "</scan><range><min>0.1</min><max>5</max></range></ray></sensor>");
  EXPECT_EQ(test::kindOf(bare), "lidar");
}

TEST(SensorsRegistry, KindsThatDisagreeAreNamed) {
  std::vector<SensorKind> kinds;
  for (const std::string& id : {"lidar", "range", "sonar"}) {
    for (const SensorKind& k : sensorKinds()) {
      if (k.id == id || (id == std::string("sonar") && k.id == "hector_sonar")) kinds.push_back(k);
    }
  }
  ASSERT_EQ(kinds.size(), 3u);
  EXPECT_TRUE(sensorKindProblems(kinds).empty());
  kinds[1].type_default = true;  // two defaults for "ray"
  kinds[2].plugins.push_back("libgazebo_ros_range.so");  // one plugin claimed by two ray kinds
  kinds.push_back(kinds[0]);  // lidar twice
  const std::vector<std::string> problems = sensorKindProblems(kinds);
  EXPECT_THAT(problems, ::testing::Contains("sensor kind 'lidar' is registered twice"));
  EXPECT_THAT(problems, ::testing::Contains("plugin 'libgazebo_ros_range.so' is claimed by sensor "
                                            "kinds 'range' and 'hector_sonar'"));
  EXPECT_THAT(problems, ::testing::Contains(::testing::HasSubstr(
                            "sensor type 'ray' is shared by kinds lidar, range, hector_sonar, lidar, of "
                            "which 3 (not 1) is its type_default")));
}

TEST(SensorsRegistry, OpenniDefaultsAreTheSimulatorsTopics) {
  // Without imageTopicName openni_kinect publishes <cameraName>/ir/image_raw.
  const SensorSpec s = sensorFrom(depthSensor("libgazebo_ros_openni_kinect.so", ""));
  EXPECT_EQ(test::kindOf(s), "depth_camera");
  const std::vector<SensorTopic> t = sensorTopics(s, "r");
  ASSERT_THAT(topicNames(t), ElementsAre("/rs/ir/image_raw", "/rs/depth/image_raw", "/rs/points",
                                         "/rs/ir/camera_info", "/rs/depth/camera_info"));
  EXPECT_DOUBLE_EQ(t[0].rate, 20.0);
  EXPECT_EQ(t[2].msg_type, "sensor_msgs/PointCloud2");
  EXPECT_DOUBLE_EQ(t[3].rate, 10.0);
}

TEST(SensorsRegistry, DepthCameraPluginAsOpenni) {
  const SensorSpec s = sensorFrom(depthSensor("/opt/x/libgazebo_ros_depth_camera.so",
                                              "<imageTopicName>rgb/image_raw</imageTopicName>"));
  EXPECT_EQ(test::kindOf(s), "depth_camera");
  const std::vector<SensorTopic> t = sensorTopics(s, "r");
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t[0].topic, "/rs/rgb/image_raw");
}

TEST(SensorsRegistry, CameraTopicsAndNoPlugin) {
  const SensorSpec cam = sensorFrom(std::string("<sensor type='camera' name='c'>") +
                                    "<update_rate>30</update_rate>" + kCameraBody +
                                    "<plugin name='p' filename='libgazebo_ros_camera.so'>"
                                    "<cameraName>cam</cameraName><robotNamespace>/r</robotNamespace>"
                                    "</plugin></sensor>");
  EXPECT_EQ(test::kindOf(cam), "camera");
  const std::vector<SensorTopic> t = sensorTopics(cam, "r");
  ASSERT_THAT(topicNames(t), ElementsAre("/r/cam/image_raw", "/r/cam/camera_info"));
  EXPECT_DOUBLE_EQ(t[1].rate, 30.0);
  // Gazebo renders a camera without a gazebo_ros plugin but publishes nothing.
  const SensorSpec bare =
      sensorFrom(std::string("<sensor type='camera' name='c'>") + kCameraBody + "</sensor>");
  EXPECT_TRUE(sensorTopics(bare, "r").empty());
}

TEST(SensorsRegistry, BadSensorThrowsNamingIt) {
  const SensorSpec bad = sensorFrom(
      "<sensor type='ray' name='broken'><ray><scan><horizontal><samples>0</samples>"
      "</horizontal></scan><range><min>0.1</min><max>5</max></range></ray></sensor>");
  try {
    sensorTopics(bad, "r");
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("broken"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("samples"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tianracer_sim
