// Camera and depth camera sensors: configuration from the seed's <sensor> elements, CameraInfo
// formulas, validation errors, noise statistics, depth cutoffs and the organized cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "tianracer_sim/render/camera_sensor.h"
#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/render/png_writer.h"

namespace tianracer_sim {
namespace {

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// What the model loader makes of a <sensor> element (name, type, rate, xml, plugins).
SensorSpec specFromXml(const std::string& xml, const std::string& link) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS) << xml;
  const tinyxml2::XMLElement* root = doc.RootElement();
  SensorSpec spec;
  spec.name = root->Attribute("name");
  spec.type = root->Attribute("type");
  spec.link = link;
  spec.xml = xml;
  spec.line = 7;
  if (const auto* rate = root->FirstChildElement("update_rate")) {
    spec.update_rate = std::stod(rate->GetText());
  }
  for (const auto* c = root->FirstChildElement("plugin"); c; c = c->NextSiblingElement("plugin")) {
    PluginSpec p;
    p.name = c->Attribute("name");
    p.filename = c->Attribute("filename");
    for (const auto* param = c->FirstChildElement(); param; param = param->NextSiblingElement()) {
      p.params[param->Name()] = param->GetText() ? param->GetText() : "";
    }
    spec.plugins.push_back(p);
  }
  return spec;
}

SensorSpec seedCamera() { return specFromXml(readFile(TEST_DATA_DIR "/render/seed_camera.xml"), "camera"); }
SensorSpec seedRealSense() {
  return specFromXml(readFile(TEST_DATA_DIR "/render/seed_real_sense.xml"), "real_sense");
}

// Replaces the first occurrence of `from` in the sensor's XML (and its plugin params again).
SensorSpec edited(const SensorSpec& spec, const std::string& from, const std::string& to) {
  std::string xml = spec.xml;
  const auto at = xml.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  xml.replace(at, from.size(), to);
  return specFromXml(xml, spec.link);
}

TEST(RenderCameraConfig, SeedCamera) {
  std::vector<std::string> warnings;
  const CameraConfig c = parseCameraConfig(seedCamera(), [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(c.name, "camera1");
  EXPECT_DOUBLE_EQ(c.horizontal_fov, 1.3962634);
  EXPECT_EQ(c.width, 800);
  EXPECT_EQ(c.height, 800);
  EXPECT_EQ(c.format, ImageFormat::kR8G8B8);
  EXPECT_DOUBLE_EQ(c.near_clip, 0.02);
  EXPECT_DOUBLE_EQ(c.far_clip, 300.0);
  EXPECT_TRUE(c.noise);
  EXPECT_DOUBLE_EQ(c.noise_stddev, 0.007);
  EXPECT_TRUE(c.has_plugin);
  EXPECT_EQ(c.camera_name, "rrbot/camera1");
  EXPECT_EQ(c.image_topic, "image_raw");
  EXPECT_EQ(c.camera_info_topic, "camera_info");
  EXPECT_EQ(c.frame_name, "camera");
  EXPECT_EQ(c.opticalFrame(), "camera_optical_frame");
  EXPECT_DOUBLE_EQ(c.update_rate, 30.0);
  EXPECT_DOUBLE_EQ(c.publishRate(), 30.0);  // updateRate 0 = the sensor rate
  EXPECT_DOUBLE_EQ(c.hack_baseline, 0.07);
}

TEST(RenderCameraConfig, SeedCameraInfo) {
  const CameraInfo info = makeCameraInfo(parseCameraConfig(seedCamera()));
  EXPECT_EQ(info.frame_id, "camera_optical_frame");
  EXPECT_EQ(info.width, 800);
  EXPECT_EQ(info.height, 800);
  EXPECT_EQ(info.distortion_model, "plumb_bob");
  EXPECT_NEAR(info.K[0], 476.70, 0.005);
  EXPECT_NEAR(info.K[4], 476.70, 0.005);
  EXPECT_DOUBLE_EQ(info.K[2], 400.5);
  EXPECT_DOUBLE_EQ(info.K[5], 400.5);
  EXPECT_DOUBLE_EQ(info.K[8], 1.0);
  EXPECT_DOUBLE_EQ(info.K[1], 0.0);
  EXPECT_NEAR(info.P[3], -33.37, 0.005);
  EXPECT_DOUBLE_EQ(info.P[0], info.K[0]);
  EXPECT_DOUBLE_EQ(info.P[2], 400.5);
  EXPECT_DOUBLE_EQ(info.P[6], 400.5);
  EXPECT_DOUBLE_EQ(info.P[10], 1.0);
  EXPECT_DOUBLE_EQ(info.P[7], 0.0);
  for (int i = 0; i < 9; ++i) EXPECT_DOUBLE_EQ(info.R[i], i % 4 == 0 ? 1.0 : 0.0);
  for (double d : info.D) EXPECT_DOUBLE_EQ(d, 0.0);
}

TEST(RenderCameraConfig, DistortionOrderIsPlumbBob) {
  SensorSpec spec = seedCamera();
  for (auto& kv : spec.plugins[0].params) {
    if (kv.first == "distortionK1") kv.second = "0.1";
    if (kv.first == "distortionK2") kv.second = "0.2";
    if (kv.first == "distortionK3") kv.second = "0.3";
    if (kv.first == "distortionT1") kv.second = "0.4";
    if (kv.first == "distortionT2") kv.second = "0.5";
  }
  std::vector<std::string> warnings;
  const CameraInfo info = makeCameraInfo(parseCameraConfig(spec, [&](const std::string& w) { warnings.push_back(w); }));
  EXPECT_EQ(info.D, (std::array<double, 5>{0.1, 0.2, 0.4, 0.5, 0.3}));  // k1 k2 t1 t2 k3
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("not distorted"), std::string::npos) << warnings[0];
}

TEST(RenderCameraConfig, SeedRealSense) {
  const DepthCameraConfig d = parseDepthCameraConfig(seedRealSense());
  EXPECT_EQ(d.camera.width, 640);
  EXPECT_EQ(d.camera.height, 480);
  EXPECT_DOUBLE_EQ(d.camera.update_rate, 20.0);
  EXPECT_DOUBLE_EQ(d.camera.publishRate(), 10.0);
  EXPECT_EQ(d.camera.camera_name, "real_sense");
  EXPECT_EQ(d.camera.image_topic, "rgb/image_raw");
  EXPECT_EQ(d.camera.camera_info_topic, "rgb/camera_info");
  EXPECT_EQ(d.depth_image_topic, "depth/image_raw");
  EXPECT_EQ(d.depth_camera_info_topic, "depth/camera_info");
  EXPECT_EQ(d.point_cloud_topic, "depth/points");
  EXPECT_DOUBLE_EQ(d.point_cloud_cutoff, 0.4);
  EXPECT_DOUBLE_EQ(d.point_cloud_cutoff_max, 5.0);
  EXPECT_DOUBLE_EQ(d.baseline, 0.1);
  EXPECT_FALSE(d.camera.noise);
  EXPECT_EQ(d.camera.opticalFrame(), "real_sense_optical_frame");
  const CameraInfo info = makeCameraInfo(d.camera);
  EXPECT_NEAR(info.K[0], 554.60, 0.005);
  EXPECT_DOUBLE_EQ(info.K[2], 320.5);
  EXPECT_DOUBLE_EQ(info.K[5], 240.5);
  EXPECT_DOUBLE_EQ(info.P[3], 0.0);  // openni_kinect reads hackBaseline, not <baseline>
}

TEST(RenderCameraConfig, DefaultsWithoutPlugin) {
  const SensorSpec spec = specFromXml(
      "<sensor name='bare' type='camera'><camera><image><width>64</width><height>32</height></image></camera></sensor>",
      "head");
  const CameraConfig c = parseCameraConfig(spec);
  EXPECT_FALSE(c.has_plugin);
  EXPECT_DOUBLE_EQ(c.horizontal_fov, 1.047);
  EXPECT_DOUBLE_EQ(c.near_clip, 0.1);
  EXPECT_DOUBLE_EQ(c.far_clip, 100.0);
  EXPECT_EQ(c.frame_name, "head");
  const DepthCameraConfig d = parseDepthCameraConfig(
      specFromXml("<sensor name='d' type='depth'><camera/><plugin name='k' filename='libgazebo_ros_openni_kinect.so'/></sensor>", "l"));
  EXPECT_EQ(d.camera.image_topic, "ir/image_raw");  // openni_kinect's own defaults
  EXPECT_EQ(d.camera.camera_info_topic, "ir/camera_info");
  EXPECT_EQ(d.point_cloud_topic, "points");
}

TEST(RenderCameraConfig, UnknownElementsAndParametersAreReported) {
  SensorSpec spec = edited(seedCamera(), "<horizontal_fov>", "<zoom>2</zoom><horizontal_fov>");
  spec.plugins[0].params["imageTopic"] = "typo";
  std::vector<std::string> warnings;
  parseCameraConfig(spec, [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("<camera><zoom>"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("<imageTopic>"), std::string::npos) << warnings[1];
  EXPECT_NE(warnings[1].find("camera1"), std::string::npos) << warnings[1];
}

// Each bad value: a CameraError whose text names the sensor and the value.
void expectError(const SensorSpec& spec, const std::vector<std::string>& needles, bool depth = false) {
  try {
    if (depth) parseDepthCameraConfig(spec);
    else parseCameraConfig(spec);
    ADD_FAILURE() << "expected CameraError for " << needles[0];
  } catch (const CameraError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("'" + spec.name + "'"), std::string::npos) << what;
    for (const auto& n : needles) EXPECT_NE(what.find(n), std::string::npos) << "'" << n << "' not in: " << what;
  }
}

TEST(RenderCameraConfig, ValidationErrors) {
  const SensorSpec seed = seedCamera();
  expectError(edited(seed, "<width>800", "<width>0"), {"<image><width> 0", "1..8192"});
  expectError(edited(seed, "<width>800", "<width>-3"), {"<image><width> -3"});
  expectError(edited(seed, "<width>800", "<width>8193"), {"<image><width> 8193"});
  expectError(edited(seed, "<height>800", "<height>0"), {"<image><height> 0"});
  expectError(edited(seed, "<height>800", "<height>10000"), {"<image><height> 10000"});
  expectError(edited(seed, "<width>800", "<width>wide"), {"<image><width> 'wide' is not a number"});
  expectError(edited(seed, "<horizontal_fov>1.3962634", "<horizontal_fov>0"), {"<horizontal_fov> 0", "(0, pi)"});
  expectError(edited(seed, "<horizontal_fov>1.3962634", "<horizontal_fov>3.2"), {"<horizontal_fov> 3.2"});
  expectError(edited(seed, "<horizontal_fov>1.3962634", "<horizontal_fov>-1"), {"<horizontal_fov> -1"});
  expectError(edited(seed, "<near>0.02", "<near>300"), {"<clip><near> 300", "<clip><far> 300"});
  expectError(edited(seed, "<near>0.02", "<near>400"), {"<clip><near> 400"});
  expectError(edited(seed, "<near>0.02", "<near>0"), {"<clip><near> 0", "> 0"});
  expectError(edited(seed, "<format>R8G8B8", "<format>BAYER_RGGB8"), {"'BAYER_RGGB8'", "not supported"});
  expectError(edited(seed, "<type>gaussian", "<type>poisson"), {"'poisson'"});
  expectError(edited(seed, "<stddev>0.007", "<stddev>-0.1"), {"<noise><stddev>"});
  SensorSpec broken = seed;  // mismatched tags
  broken.xml.replace(broken.xml.find("<camera name=\"head\">"), 20, "<kamera>");
  expectError(broken, {"its XML does not parse (line 4)", "MISMATCHED_ELEMENT", "kamera"});
  expectError(edited(seedRealSense(), "<pointCloudCutoff>0.4", "<pointCloudCutoff>6"),
              {"<pointCloudCutoff> 6", "<pointCloudCutoffMax> 5"}, true);
  SensorSpec no_camera = specFromXml("<sensor name='nocam' type='camera'><update_rate>1</update_rate></sensor>", "l");
  expectError(no_camera, {"no <camera> element"});
  // L8 is accepted.
  EXPECT_EQ(parseCameraConfig(edited(seed, "<format>R8G8B8", "<format>L8")).format, ImageFormat::kL8);
}

// --- Sensors -------------------------------------------------------------------------------------

// A wall of `material` whose face is the plane x = distance (world frame), camera at origin.
Scene wallScene(double distance, const std::string& material = "Gazebo/Grey") {
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  scene.lights[0].direction = Eigen::Vector3d(0.6, -0.3, -0.74);
  scene.addBody(SceneBody{"wall::link", "wall", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.shape.type = ShapeType::kBox;
  item.shape.size = Eigen::Vector3d(0.2, 100.0, 100.0);
  item.X_BS.translation() = Eigen::Vector3d(distance + 0.1, 0, 0);
  item.material = findGazeboMaterial(material)->material;
  scene.items.push_back(item);
  return scene;
}

DepthCameraConfig smallDepthConfig() {
  DepthCameraConfig d = parseDepthCameraConfig(seedRealSense());
  d.camera.width = 64;
  d.camera.height = 48;
  return d;
}

TEST(RenderCameraSensor, NoiseStatisticsMatchTheConfiguredStddev) {
  Renderer renderer;
  Scene scene;  // only the sky: every pixel has the same colour before noise
  scene.sky = Eigen::Vector4f(0.5f, 0.5f, 0.5f, 1.0f);
  CameraConfig c = parseCameraConfig(seedCamera());
  c.width = 256;
  c.height = 256;
  for (double stddev : {0.007, 0.05}) {
    c.noise_stddev = stddev;
    CameraSensor clean_config_sensor = [&] {
      CameraConfig q = c;
      q.noise = false;
      return CameraSensor(q, renderer);
    }();
    clean_config_sensor.render(scene, Eigen::Isometry3d::Identity());
    const int base = clean_config_sensor.image()[0];
    CameraSensor cam(c, renderer);
    cam.render(scene, Eigen::Isometry3d::Identity());
    const auto& img = cam.image();
    double sum = 0, sum2 = 0;
    const std::size_t pixels = img.size() / 3;
    for (std::size_t i = 0; i < pixels; ++i) {
      // One sample per pixel, the same on all three channels (as Gazebo).
      ASSERT_EQ(img[3 * i], img[3 * i + 1]);
      ASSERT_EQ(img[3 * i], img[3 * i + 2]);
      const double n = (img[3 * i] - base) / 255.0;
      sum += n;
      sum2 += n * n;
    }
    const double mean = sum / pixels, sd = std::sqrt(sum2 / pixels - mean * mean);
    EXPECT_NEAR(sd, stddev, 0.1 * stddev) << "stddev " << stddev;
    EXPECT_NEAR(mean, 0.0, 0.1 * stddev);
    // Deterministic: the same seed gives the same first frame; the next frame differs.
    CameraSensor again(c, renderer);
    again.render(scene, Eigen::Isometry3d::Identity());
    EXPECT_EQ(again.image(), cam.image());
    cam.render(scene, Eigen::Isometry3d::Identity());
    EXPECT_NE(again.image(), cam.image());
  }
}

TEST(RenderCameraSensor, CameraSeesItsLinkPoseAndSensorPose) {
  Renderer renderer;
  const Scene scene = wallScene(3.0, "Gazebo/Blue");
  CameraConfig c = parseCameraConfig(seedCamera());
  c.width = 40;
  c.height = 40;
  c.noise = false;
  c.X_LS.translation() = Eigen::Vector3d(1.0, 0, 0);  // 1 m ahead of its link
  CameraSensor cam(c, renderer);
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  cam.render(scene, X_WL);
  const uint8_t* px = &cam.image()[(20 * 40 + 20) * 3];
  EXPECT_GT(px[2], 150);
  EXPECT_LT(px[0], 40);
  EXPECT_EQ(cam.renderCount(), 1u);
}

TEST(RenderCameraSensor, L8IsLuminance) {
  Renderer renderer;
  Scene scene;
  scene.sky = Eigen::Vector4f(1.0f, 0.0f, 0.0f, 1.0f);
  CameraConfig c = parseCameraConfig(edited(seedCamera(), "<format>R8G8B8", "<format>L8"));
  c.width = 8;
  c.height = 8;
  c.noise = false;
  CameraSensor cam(c, renderer);
  cam.render(scene, Eigen::Isometry3d::Identity());
  ASSERT_EQ(cam.image().size(), 64u);
  EXPECT_EQ(cam.channels(), 1);
  EXPECT_EQ(cam.image()[0], 76);  // 0.299 * 255
}

TEST(RenderDepthCamera, DepthAndCloudOfAWall) {
  Renderer renderer;
  DepthCameraSensor cam(smallDepthConfig(), renderer);
  const int W = 64, H = 48;
  // A wall tilted about z: depth varies across the image.
  Scene scene = wallScene(2.0, "Gazebo/Red");
  const double tilt = 0.3;
  scene.items[0].X_BS = Eigen::Translation3d(2.0, 0, 0) * Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitZ()) *
                        Eigen::Translation3d(0.1, 0, 0);
  cam.render(scene, Eigen::Isometry3d::Identity());
  const CameraInfo& info = cam.info();
  const double f = info.K[0];
  const auto& cloud = cam.cloud();
  ASSERT_EQ(cloud.size(), static_cast<std::size_t>(W * H * CloudLayout::kPointStep));
  EXPECT_TRUE(cam.cloudIsDense());
  int checked = 0;
  for (int v = 0; v < H; ++v) {
    for (int u = 0; u < W; ++u) {
      const uint8_t* p = &cloud[(v * W + u) * CloudLayout::kPointStep];
      float xyz[3];
      std::memcpy(xyz, p, sizeof(xyz));
      ASSERT_TRUE(std::isfinite(xyz[2]));
      EXPECT_FLOAT_EQ(xyz[2], cam.depth()[v * W + u]);
      // Reprojection through K: gazebo_ros's K has cx = (W+1)/2, i.e. 1-based pixel
      // indices; the cloud (x = d (u - (W-1)/2) / f) reprojects to pixel u + 1 of that
      // convention, and to u exactly with the rendered principal point (W-1)/2.
      EXPECT_NEAR(f * xyz[0] / xyz[2] + info.K[2], u + 1.0, 1e-3);
      EXPECT_NEAR(f * xyz[1] / xyz[2] + info.K[5], v + 1.0, 1e-3);
      // The point lies on the wall: in the link frame (x = z_O, y = -x_O) x = 2 - tan(t) y.
      const double xl = xyz[2], yl = -xyz[0];
      EXPECT_NEAR(xl, 2.0 - std::tan(tilt) * yl, 1e-4);
      // Colour: red, packed 0x00RRGGBB (R in bits 16-23).
      uint32_t rgb = 0;
      std::memcpy(&rgb, p + CloudLayout::kOffsetRgb, 4);
      const uint8_t* px = &cam.image()[(v * W + u) * 3];
      EXPECT_EQ(rgb, (uint32_t(px[0]) << 16) | (uint32_t(px[1]) << 8) | px[2]);
      EXPECT_GT(rgb >> 16, 150u);
      EXPECT_LT(rgb & 0xff, 40u);
      ++checked;
    }
  }
  EXPECT_EQ(checked, W * H);
}

TEST(RenderDepthCamera, BeyondTheCutoffsIsNaN) {
  Renderer renderer;
  DepthCameraSensor cam(smallDepthConfig(), renderer);  // cutoff 0.4, cutoffMax 5
  const std::size_t n = 64 * 48;
  auto count_nan = [&] {
    std::size_t nan_depth = 0, nan_cloud = 0;
    for (std::size_t i = 0; i < n; ++i) {
      nan_depth += std::isnan(cam.depth()[i]);
      float xyz[3];
      std::memcpy(xyz, &cam.cloud()[i * CloudLayout::kPointStep], sizeof(xyz));
      nan_cloud += std::isnan(xyz[0]) && std::isnan(xyz[1]) && std::isnan(xyz[2]);
    }
    EXPECT_EQ(nan_depth, nan_cloud);
    return nan_depth;
  };
  cam.render(wallScene(6.0), Eigen::Isometry3d::Identity());  // beyond cutoffMax (but < far 8)
  EXPECT_EQ(count_nan(), n);
  EXPECT_FALSE(cam.cloudIsDense());
  cam.render(wallScene(0.3), Eigen::Isometry3d::Identity());  // nearer than the cutoff
  EXPECT_EQ(count_nan(), n);
  cam.render(wallScene(2.0), Eigen::Isometry3d::Identity());
  EXPECT_EQ(count_nan(), 0u);
  EXPECT_TRUE(cam.cloudIsDense());
  EXPECT_NEAR(cam.depth()[24 * 64 + 32], 2.0, 1e-4);
  cam.render(Scene{}, Eigen::Isometry3d::Identity());  // nothing at all: sky
  EXPECT_EQ(count_nan(), n);
  EXPECT_EQ(cam.renderCount(), 4u);
}

TEST(RenderDepthCamera, OnlyWhatIsAskedFor) {
  Renderer renderer;
  DepthCameraSensor cam(smallDepthConfig(), renderer);
  const uint64_t before = renderer.frameCount();
  cam.render(wallScene(2.0), Eigen::Isometry3d::Identity(), DepthOutputs{false, false, false});
  EXPECT_EQ(renderer.frameCount(), before);  // nobody wants anything: no rendering
  cam.render(wallScene(2.0), Eigen::Isometry3d::Identity(), DepthOutputs{false, true, false});
  EXPECT_EQ(renderer.frameCount(), before + 1);
  EXPECT_NEAR(cam.depth()[24 * 64 + 32], 2.0, 1e-4);
}

TEST(RenderPng, WritesColourAndDepth) {
  std::vector<uint8_t> rgb(4 * 3 * 3, 200);
  const std::string path = ::testing::TempDir() + "render_test.png";
  writePng(path, rgb.data(), 4, 3, 3);
  const std::string bytes = readFile(path);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(1, 3), "PNG");
  std::vector<float> depth = {1.0f, NAN, 2.0f, INFINITY};
  std::vector<uint8_t> colours;
  depthToColor(depth.data(), 4, 1, 1.0, 2.0, &colours);
  EXPECT_EQ(colours[3], 0);  // NaN is black
  EXPECT_EQ(colours[4], 0);
  EXPECT_EQ(colours[9], 0);  // inf too
  EXPECT_GT(colours[0] + colours[1] + colours[2], 0);
  writeDepthPng(path, depth.data(), 4, 1, 1.0, 2.0);
  try {
    writePng("/nonexistent/dir/x.png", rgb.data(), 4, 3, 3);
    ADD_FAILURE();
  } catch (const PngError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/x.png"), std::string::npos);
  }
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
