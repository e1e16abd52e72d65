// Multicamera sensors (gazebo_ros_multicamera): a stereo pair's configuration, topics, camera
// infos (the right camera's P[3] = -f * hackBaseline), its rendered disparity against the
// published P, and the bad input that leaves the sensor out.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/multicamera_config.h"
#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "common_test_support.h"
#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using test::readFile;

// What the model loader makes of a <sensor> element (name, type, rate, pose, xml, plugins).
SensorSpec specFromXml(const std::string& xml) {
  SensorSpec spec = test::specFromXml(xml, "stereo_link", "car.urdf", 12);
  spec.X_LS.translation() = Eigen::Vector3d(0.1, 0, 0.05);  // the file's sensor <pose>
  return spec;
}

const std::string kStereoXml = readFile(TEST_DATA_DIR "/render/stereo_multicamera.xml");

SensorSpec stereo() { return specFromXml(kStereoXml); }

// The stereo sensor with the first occurrence of `from` replaced by `to`.
SensorSpec edited(const std::string& from, const std::string& to) {
  return specFromXml(test::replaced(kStereoXml, from, to));
}

std::string errorOf(const SensorSpec& spec) {
  return test::errorText<CameraError>([&] { parseMultiCameraConfig(spec, "car_a"); });
}

TEST(SensorsMultiCamera, StereoPairConfiguration) {
  std::vector<std::string> warnings;
  const MultiCameraConfig m =
      parseMultiCameraConfig(stereo(), "car_a", [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_TRUE(m.has_plugin);
  ASSERT_EQ(m.cameras.size(), 2u);
  EXPECT_DOUBLE_EQ(m.publishRate(), 15.0);  // updateRate 0: the sensor's rate
  const CameraConfig& l = m.cameras[0];
  const CameraConfig& r = m.cameras[1];
  EXPECT_EQ(l.name, "left");
  EXPECT_EQ(r.name, "right");
  // gazebo_ros_multicamera's topics: <cameraName>/left and <cameraName>/right.
  EXPECT_EQ(l.camera_name, "stereo/camera/left");
  EXPECT_EQ(r.camera_name, "stereo/camera/right");
  EXPECT_EQ(l.format, ImageFormat::kR8G8B8);
  EXPECT_EQ(r.format, ImageFormat::kB8G8R8);
  EXPECT_EQ(l.width, 320);
  EXPECT_EQ(r.height, 240);
  EXPECT_TRUE(l.noise);
  EXPECT_DOUBLE_EQ(l.noise_stddev, 0.007);
  EXPECT_FALSE(r.noise);
  EXPECT_NE(l.noise_seed, r.noise_seed);
  // Each camera's pose: the sensor's pose, then the camera's own.
  EXPECT_TRUE(l.X_LS.translation().isApprox(Eigen::Vector3d(0.1, 0, 0.05)));
  EXPECT_TRUE(r.X_LS.translation().isApprox(Eigen::Vector3d(0.1, -0.07, 0.05)));
  // One frameName for both, as Gazebo stamps them.
  EXPECT_EQ(l.opticalFrame(), "stereo_link_optical_frame");
  EXPECT_EQ(r.opticalFrame(), "stereo_link_optical_frame");

  // Only the right camera carries the baseline: P[3] = -f * hackBaseline.
  const CameraInfo li = makeCameraInfo(l), ri = makeCameraInfo(r);
  const double f = 320 / (2.0 * std::tan(1.3962634 / 2.0));
  EXPECT_NEAR(li.K[0], f, 1e-9);
  EXPECT_DOUBLE_EQ(li.P[3], 0.0);
  EXPECT_NEAR(ri.P[3], -f * 0.07, 1e-9);
  EXPECT_LT(ri.P[3], 0.0);
  EXPECT_DOUBLE_EQ(ri.K[2], 160.5);
}

TEST(SensorsMultiCamera, RegistryListsEveryCamerasTopics) {
  const SensorSpec spec = stereo();
  const SensorKind* kind = findSensorKind(spec);
  ASSERT_NE(kind, nullptr);
  EXPECT_EQ(kind->id, "multicamera");
  const std::vector<SensorTopic> topics = sensorTopics(spec, "car_a");
  ASSERT_THAT(test::topicNames(topics),
              ::testing::ElementsAre(
                  "/stereo/camera/left/image_raw", "/stereo/camera/left/camera_info",
                  "/stereo/camera/right/image_raw", "/stereo/camera/right/camera_info"));
  EXPECT_EQ(topics[0].msg_type, "sensor_msgs/Image");
  EXPECT_DOUBLE_EQ(topics[0].rate, 15.0);
  EXPECT_EQ(topics[1].msg_type, "sensor_msgs/CameraInfo");
}

TEST(SensorsMultiCamera, SuffixesFramesAndNamespace) {
  // Not a left/right pair: each camera's own name is its suffix.
  std::string xml = kStereoXml;
  xml.replace(xml.find("name=\"left\""), 11, "name=\"front\"");
  xml.replace(xml.find("name=\"right\""), 12, "name=\"rear\"");
  MultiCameraConfig m = parseMultiCameraConfig(specFromXml(xml), "car_a");
  EXPECT_EQ(m.cameras[0].camera_name, "stereo/camera/front");
  EXPECT_EQ(m.cameras[1].camera_name, "stereo/camera/rear");
  EXPECT_DOUBLE_EQ(makeCameraInfo(m.cameras[1]).P[3], 0.0);  // no "right" in its name

  // <cameraSuffixes>, one <frameName> per camera, <robotNamespace>, <updateRate>.
  SensorSpec spec = stereo();
  spec.plugins[0].params["cameraSuffixes"] = "/l, /r";
  spec.plugins[0].params["frameName"] = "left_cam, right_cam";
  spec.plugins[0].params["robotNamespace"] = "/car_a";
  spec.plugins[0].params["updateRate"] = "5";
  m = parseMultiCameraConfig(spec, "car_a");
  EXPECT_EQ(m.cameras[0].camera_name, "stereo/camera/l");
  EXPECT_EQ(m.cameras[1].camera_name, "stereo/camera/r");
  EXPECT_EQ(m.cameras[0].opticalFrame(), "left_cam_optical_frame");
  EXPECT_EQ(m.cameras[1].opticalFrame(), "right_cam_optical_frame");
  EXPECT_DOUBLE_EQ(m.publishRate(), 5.0);
  const std::vector<SensorTopic> topics = sensorTopics(spec, "car_a");
  EXPECT_EQ(topics[2].topic, "/car_a/stereo/camera/r/image_raw");

  // Without frameName: the sensor's link.
  spec = stereo();
  spec.plugins[0].params.erase("frameName");
  EXPECT_EQ(parseMultiCameraConfig(spec, "car_a").cameras[1].opticalFrame(),
            "stereo_link_optical_frame");
}

TEST(SensorsMultiCamera, WithoutPluginNothingIsPublished) {
  SensorSpec spec = stereo();
  spec.plugins.clear();
  EXPECT_FALSE(parseMultiCameraConfig(spec, "car_a").has_plugin);
  EXPECT_TRUE(sensorTopics(spec, "car_a").empty());
}

TEST(SensorsMultiCamera, UnknownParametersAreReported) {
  SensorSpec spec = stereo();
  spec.plugins[0].params["imageTopicNmae"] = "x";
  std::vector<std::string> warnings;
  parseMultiCameraConfig(spec, "car_a", [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("multicamera sensor 'stereo_camera'"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("<imageTopicNmae>"), std::string::npos) << warnings[0];
}

// Bad input: each message names the robot, the sensor and the value.
TEST(SensorsMultiCamera, OneCameraIsAnError) {
  const std::string xml = kStereoXml;
  const auto b = xml.find("<camera name=\"right\">");
  const auto e = xml.find("</camera>", b) + std::string("</camera>").size();
  const std::string err = errorOf(specFromXml(xml.substr(0, b) + xml.substr(e)));
  EXPECT_NE(err.find("robot 'car_a'"), std::string::npos) << err;
  EXPECT_NE(err.find("multicamera sensor 'stereo_camera'"), std::string::npos) << err;
  EXPECT_NE(err.find("has 1 <camera>"), std::string::npos) << err;
  // Placed at the <sensor>'s line of its model file, before the robot and the sensor.
  EXPECT_EQ(err.rfind("car.urdf:12: robot 'car_a': multicamera sensor 'stereo_camera' on link "
                      "'stereo_link': ", 0), 0u) << err;
  // The registry (model_info, the node) reports it the same way.
  EXPECT_THROW(sensorTopics(specFromXml(xml.substr(0, b) + xml.substr(e)), "car_a"), CameraError);
}

TEST(SensorsMultiCamera, TwoCamerasWithTheSameNameIsAnError) {
  const std::string err = errorOf(edited("<camera name=\"right\">", "<camera name=\"left\">"));
  EXPECT_NE(err.find("robot 'car_a'"), std::string::npos) << err;
  EXPECT_NE(err.find("multicamera sensor 'stereo_camera'"), std::string::npos) << err;
  EXPECT_NE(err.find("two cameras are named 'left'"), std::string::npos) << err;
}

TEST(SensorsMultiCamera, ACameraErrorKeepsTheSensorsPlaceInFront) {
  const std::string err = errorOf(edited("<width>320</width>", "<width>0</width>"));
  EXPECT_EQ(err.rfind("car.urdf:12: robot 'car_a': multicamera sensor 'stereo_camera/", 0), 0u)
      << err;
  EXPECT_NE(err.find("<image><width> 0 out of range"), std::string::npos) << err;
}

TEST(SensorsMultiCamera, OtherBadInput) {
  std::string err = errorOf(edited("<camera name=\"right\">", "<camera>"));
  EXPECT_NE(err.find("has no name"), std::string::npos) << err;
  err = errorOf(edited("0 -0.07 0 0 0 0", "0 -0.07 0 0 nan"));
  EXPECT_NE(err.find("camera 'right': <pose> '0 -0.07 0 0 nan'"), std::string::npos) << err;
  // A camera's own error names the camera and the value.
  err = errorOf(edited("<format>B8G8R8", "<format>R_FLOAT32"));
  EXPECT_NE(err.find("robot 'car_a'"), std::string::npos) << err;
  EXPECT_NE(err.find("'stereo_camera/right'"), std::string::npos) << err;
  EXPECT_NE(err.find("'R_FLOAT32'"), std::string::npos) << err;
  SensorSpec spec = stereo();
  spec.plugins[0].params["cameraSuffixes"] = "/a,/b,/c";
  err = errorOf(spec);
  EXPECT_NE(err.find("<cameraSuffixes> '/a,/b,/c' has 3 entries for 2 cameras"), std::string::npos)
      << err;
  spec = stereo();
  spec.plugins[0].params["frameName"] = "a,b,c";
  err = errorOf(spec);
  EXPECT_NE(err.find("<frameName> 'a,b,c' lists 3 frames"), std::string::npos) << err;
  spec = stereo();
  spec.plugins[0].params["hackBaseline"] = "wide";
  err = errorOf(spec);
  EXPECT_NE(err.find("<hackBaseline> 'wide'"), std::string::npos) << err;
}

// --- Rendering ---------------------------------------------------------------------------------

// A thin red disc facing the cameras, centred at p_W (the cameras look along world +x).
Scene discScene(const Eigen::Vector3d& p_W, double radius) {
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  scene.addBody(SceneBody{"disc::link", "disc", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.shape.type = ShapeType::kCylinder;
  item.shape.radius = radius;
  item.shape.length = 0.0002;
  item.X_BS = Eigen::Translation3d(p_W + Eigen::Vector3d(0.0001, 0, 0)) *
              Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY());
  item.material = findGazeboMaterial("Gazebo/Red")->material;
  scene.items.push_back(item);
  return scene;
}

// Centroid (u) of the pixels of a `bpp`-byte image that differ from its corner pixel.
double centroidU(const std::vector<uint8_t>& img, int W, int H, int bpp, int* count) {
  double su = 0;
  int n = 0;
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      if (std::memcmp(&img[(v * W + u) * bpp], &img[0], bpp) != 0) {
        su += u;
        ++n;
      }
    }
  }
  *count = n;
  return n ? su / n : -1.0;
}

TEST(SensorsMultiCamera, RightImageIsWhereTheRightCameraInfoProjects) {
  Renderer renderer;
  MultiCameraConfig m = parseMultiCameraConfig(stereo(), "car_a");
  for (CameraConfig& c : m.cameras) c.noise = false;
  CameraSensor left(m.cameras[0], renderer), right(m.cameras[1], renderer);
  // A disc 2 m ahead of the left camera (link = world), 0.1 m to its left.
  const Eigen::Vector3d p_W(0.1 + 2.0, 0.1, 0.05);
  const Scene scene = discScene(p_W, 0.2);
  left.render(scene, Eigen::Isometry3d::Identity());
  right.render(scene, Eigen::Isometry3d::Identity());
  // The disc's centre in the left optical frame: X = -y, Z = x (both from the left camera).
  const double X = -p_W.y(), Z = p_W.x() - 0.1;
  const CameraInfo& li = left.info();
  const CameraInfo& ri = right.info();
  // ROS stereo: both P project points given in the left camera's frame.
  const double u_left = (li.P[0] * X + li.P[2] * Z + li.P[3]) / Z;
  const double u_right = (ri.P[0] * X + ri.P[2] * Z + ri.P[3]) / Z;
  int n_left = 0, n_right = 0;
  EXPECT_NEAR(centroidU(left.image(), 320, 240, 3, &n_left), u_left, 0.1);
  EXPECT_NEAR(centroidU(right.image(), 320, 240, 3, &n_right), u_right, 0.1);
  EXPECT_GT(n_left, 800);
  EXPECT_NEAR(n_left, n_right, 0.05 * n_left);
  // Disparity f * B / Z, the right image left of the left one.
  EXPECT_NEAR(u_left - u_right, li.K[0] * 0.07 / Z, 1e-9);
  EXPECT_STREQ(right.encoding(), "bgr8");
}

}  // namespace
}  // namespace tianracer_sim
