// Camera and depth camera sensors: configuration from the seed's <sensor> elements, CameraInfo
// formulas, validation errors, noise statistics, depth cutoffs and the organized cloud.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/image_noise.h"
#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/render/png_writer.h"

#include "common_test_support.h"
#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using test::readFile;

// What the model loader makes of a <sensor> element (name, type, rate, xml, plugins).
SensorSpec specFromXml(const std::string& xml, const std::string& link) {
  return test::specFromXml(xml, link, "car.urdf", 7);
}

SensorSpec seedCamera() { return specFromXml(readFile(TEST_DATA_DIR "/render/seed_camera.xml"), "camera"); }
SensorSpec seedRealSense() {
  return specFromXml(readFile(TEST_DATA_DIR "/render/seed_real_sense.xml"), "real_sense");
}

// Replaces the first occurrence of `from` in the sensor's XML (and its plugin params again).
SensorSpec edited(const SensorSpec& spec, const std::string& from, const std::string& to) {
  return specFromXml(test::replaced(spec.xml, from, to), spec.link);
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
  ASSERT_EQ(warnings.size(), 1u);  // D is not what the (absent) <distortion> does to images
  EXPECT_NE(warnings[0].find("differs from the <distortion> applied to the images"),
            std::string::npos) << warnings[0];
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
  // Placed at the <sensor>'s line of its model file, then the sensor.
  expectError(edited(seed, "<width>800", "<width>0"),
              {"car.urdf:7: camera sensor 'camera1' on link 'camera': <image><width> 0 out of "
               "range"});
  expectError(edited(seed, "<width>800", "<width>-3"), {"<image><width> -3"});
  expectError(edited(seed, "<width>800", "<width>8193"), {"<image><width> 8193"});
  expectError(edited(seed, "<height>800", "<height>0"), {"<image><height> 0"});
  expectError(edited(seed, "<height>800", "<height>10000"), {"<image><height> 10000"});
  // Each side within 8192, but 8192 x 8192 is beyond the pixel budget (issue 43).
  expectError(edited(edited(seed, "<height>800", "<height>8192"), "<width>800", "<width>8192"),
              {"<image> 8192 x 8192 pixels is out of range (<= 33554432 pixels"});
  expectError(edited(seed, "<width>800", "<width>wide"), {"<image><width> 'wide' is not a number"});
  expectError(edited(seed, "<horizontal_fov>1.3962634", "<horizontal_fov>0"), {"<horizontal_fov> 0", "(0, pi)"});
  expectError(edited(seed, "<horizontal_fov>1.3962634", "<horizontal_fov>3.2"), {"<horizontal_fov> 3.2"});
  expectError(edited(seed, "<horizontal_fov>1.3962634", "<horizontal_fov>-1"), {"<horizontal_fov> -1"});
  expectError(edited(seed, "<near>0.02", "<near>300"), {"<clip><near> 300", "<clip><far> 300"});
  expectError(edited(seed, "<near>0.02", "<near>400"), {"<clip><near> 400"});
  expectError(edited(seed, "<near>0.02", "<near>0"), {"<clip><near> 0", "> 0"});
  expectError(edited(seed, "<format>R8G8B8", "<format>R_FLOAT16"),
              {"camera1", "<image><format> 'R_FLOAT16'", "Gazebo format that is not simulated", "left out"});
  expectError(edited(seed, "<format>R8G8B8", "<format>R_FLOAT32"), {"'R_FLOAT32'", "not simulated"});
  expectError(edited(seed, "<format>R8G8B8", "<format>RGBA8"), {"'RGBA8' is not a Gazebo image format"});
  expectError(edited(seed, "<type>gaussian", "<type>poisson"), {"'poisson'"});
  expectError(edited(seed, "<stddev>0.007", "<stddev>-0.1"), {"<noise><stddev>"});
  SensorSpec broken = seed;  // mismatched tags
  broken.xml.replace(broken.xml.find("<camera name=\"head\">"), 20, "<kamera>");
  expectError(broken, {"its XML does not parse (line 4 of the copy)", "MISMATCHED_ELEMENT", "kamera"});
  expectError(edited(seedRealSense(), "<pointCloudCutoff>0.4", "<pointCloudCutoff>6"),
              {"<pointCloudCutoff> 6", "<pointCloudCutoffMax> 5"}, true);
  SensorSpec no_camera = specFromXml("<sensor name='nocam' type='camera'><update_rate>1</update_rate></sensor>", "l");
  expectError(no_camera, {"no <camera> element"});
  // Gazebo's formats and their *_INT* aliases are accepted.
  const std::vector<std::pair<std::string, ImageFormat>> formats = {
      {"L8", ImageFormat::kL8},         {"L_INT8", ImageFormat::kL8},
      {"L16", ImageFormat::kL16},       {"L_INT16", ImageFormat::kL16},
      {"B8G8R8", ImageFormat::kB8G8R8}, {"BGR_INT8", ImageFormat::kB8G8R8},
      {"RGB_INT8", ImageFormat::kR8G8B8}, {"R16G16B16", ImageFormat::kR16G16B16},
      {"RGB_INT16", ImageFormat::kR16G16B16}, {"BAYER_RGGB8", ImageFormat::kBayerRGGB8},
      {"BAYER_BGGR8", ImageFormat::kBayerBGGR8}, {"BAYER_GBRG8", ImageFormat::kBayerGBRG8},
      {"BAYER_GRBG8", ImageFormat::kBayerGRBG8}};
  for (const auto& f : formats) {
    EXPECT_EQ(parseCameraConfig(edited(seed, "<format>R8G8B8", "<format>" + f.first)).format, f.second)
        << f.first;
  }
  EXPECT_STREQ(imageEncoding(ImageFormat::kR8G8B8), "rgb8");
  EXPECT_STREQ(imageEncoding(ImageFormat::kB8G8R8), "bgr8");
  EXPECT_STREQ(imageEncoding(ImageFormat::kL8), "mono8");
  EXPECT_STREQ(imageEncoding(ImageFormat::kL16), "mono16");
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

// The 3-channel noise runs 16 pixels at a time with saturating byte operations (SSE2); the
// one-channel path is plain per-byte arithmetic. With the same seed both draw the same samples,
// so each channel of a colour image must come out as that channel alone as a mono image: byte
// for byte, saturation at 0 and 255 and the tail after the last 16-pixel group included.
TEST(ImageNoise, ColourPathGivesTheSameBytesAsThePerChannelPath) {
  const std::size_t pixels = 16 * 37 + 7;  // a tail that is neither a group nor a block
  std::vector<uint8_t> rgb(3 * pixels);
  uint32_t x = 12345;
  for (auto& b : rgb) {
    x = x * 1664525u + 1013904223u;
    b = static_cast<uint8_t>(x >> 24);
  }
  for (const double stddev : {0.007, 0.3}) {  // 0.3: many samples saturate at both ends
    for (int frame = 0; frame < 3; ++frame) {
      std::vector<uint8_t> colour = rgb;
      ImageNoise noise(0.01, stddev, 7);
      for (int f = 0; f <= frame; ++f) {
        colour = rgb;
        noise.apply(colour.data(), pixels, 3);
      }
      std::size_t changed = 0;
      for (int c = 0; c < 3; ++c) {
        std::vector<uint8_t> mono(pixels);
        for (std::size_t i = 0; i < pixels; ++i) mono[i] = rgb[3 * i + c];
        ImageNoise alone(0.01, stddev, 7);
        std::vector<uint8_t> out;
        for (int f = 0; f <= frame; ++f) {
          out = mono;
          alone.apply(out.data(), pixels, 1);
        }
        for (std::size_t i = 0; i < pixels; ++i) {
          ASSERT_EQ(colour[3 * i + c], out[i]) << "stddev " << stddev << " frame " << frame << " pixel "
                                               << i << " channel " << c;
          changed += out[i] != mono[i];
        }
      }
      EXPECT_GT(changed, pixels / 2) << "the noise is visible";
    }
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
      // Reprojection through the published K lands on the pixel itself (0-based indices).
      EXPECT_NEAR(f * xyz[0] / xyz[2] + info.K[2], u, 1e-3);
      EXPECT_NEAR(f * xyz[1] / xyz[2] + info.K[5], v, 1e-3);
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

// --- Principal point: images, depth and cloud agree with the published K ---------------------

// Thin discs facing the camera (cylinders 0.2 mm long, axis along the optical axis) centred at
// optical-frame points: every point of a disc's face is at the same depth, so its image is the
// exactly scaled disc and its centroid is the projection of the disc's centre.
Scene discScene(const std::vector<Eigen::Vector3d>& centres_O, double radius) {
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  scene.addBody(SceneBody{"discs::link", "discs", true, Eigen::Isometry3d::Identity()});
  for (const Eigen::Vector3d& p : centres_O) {
    SceneItem item;
    item.shape.type = ShapeType::kCylinder;
    item.shape.radius = radius;
    item.shape.length = 0.0002;
    // Camera link = world: optical (X, Y, Z) is world (Z, -X, -Y); the disc's axis along x.
    item.X_BS = Eigen::Translation3d(p.z() + 0.0001, -p.x(), -p.y()) *
                Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY());
    item.material = findGazeboMaterial("Gazebo/Red")->material;
    scene.items.push_back(item);
  }
  return scene;
}

// Centroid (u, v) of the pixels in the box around (u0, v0) for which `hit(u, v)` holds.
template <typename Hit>
Eigen::Vector2d centroid(int W, int H, double u0, double v0, int half, Hit hit, int* count) {
  double su = 0, sv = 0;
  int n = 0;
  for (int v = std::max(0, int(v0) - half); v <= std::min(H - 1, int(v0) + half); ++v) {
    for (int u = std::max(0, int(u0) - half); u <= std::min(W - 1, int(u0) + half); ++u) {
      if (!hit(u, v)) continue;
      su += u;
      sv += v;
      ++n;
    }
  }
  *count = n;
  return n ? Eigen::Vector2d(su / n, sv / n) : Eigen::Vector2d(-1, -1);
}

const std::vector<Eigen::Vector3d> kDiscCentres = {
    {0.0, 0.0, 3.0}, {-1.1, -0.7, 3.0}, {1.2, 0.8, 3.5}, {0.6, -0.9, 2.5}, {-0.9, 0.6, 4.0}};

TEST(RenderPrincipalPoint, CameraImageMatchesThePublishedK) {
  Renderer renderer;
  CameraConfig c = parseCameraConfig(edited(seedCamera(), "<width>800", "<width>640"));
  c.height = 480;
  c.noise = false;
  CameraSensor cam(c, renderer);
  const CameraInfo& info = cam.info();
  EXPECT_DOUBLE_EQ(info.K[2], 320.5);  // Gazebo's (W+1)/2, kept
  EXPECT_DOUBLE_EQ(info.K[5], 240.5);
  const Scene scene = discScene(kDiscCentres, 0.15);
  cam.render(scene, Eigen::Isometry3d::Identity());
  const auto& img = cam.image();
  const uint8_t sky[3] = {img[0], img[1], img[2]};  // a corner sees only the sky
  for (const Eigen::Vector3d& p : kDiscCentres) {
    const double z = p.z() - 0.0001;  // the disc's front face
    // Projection through P (= K here: no baseline): u = (P00 X + P02 Z) / Z.
    const double u = (info.P[0] * p.x() + info.P[2] * z) / z;
    const double v = (info.P[5] * p.y() + info.P[6] * z) / z;
    int n = 0;
    const Eigen::Vector2d m = centroid(640, 480, u, v, 60, [&](int x, int y) {
      const uint8_t* px = &img[(y * 640 + x) * 3];
      return px[0] != sky[0] || px[1] != sky[1] || px[2] != sky[2];
    }, &n);
    EXPECT_GT(n, 300) << p.transpose();
    EXPECT_NEAR(m.x(), u, 0.1) << p.transpose();
    EXPECT_NEAR(m.y(), v, 0.1) << p.transpose();
  }
}

TEST(RenderPrincipalPoint, DepthCameraImageDepthAndCloudMatchThePublishedK) {
  Renderer renderer;
  DepthCameraConfig d = parseDepthCameraConfig(seedRealSense());  // 640 x 480
  d.point_cloud_cutoff_max = 10.0;
  DepthCameraSensor cam(d, renderer);
  const CameraInfo& info = cam.info();
  EXPECT_DOUBLE_EQ(info.K[2], 320.5);
  EXPECT_DOUBLE_EQ(info.K[5], 240.5);
  const int W = 640, H = 480;
  cam.render(discScene(kDiscCentres, 0.15), Eigen::Isometry3d::Identity());
  const auto& img = cam.image();
  const uint8_t sky[3] = {img[0], img[1], img[2]};
  for (const Eigen::Vector3d& p : kDiscCentres) {
    const double z = p.z() - 0.0001;
    const double u = info.K[0] * p.x() / z + info.K[2];
    const double v = info.K[4] * p.y() / z + info.K[5];
    int n_img = 0, n_depth = 0;
    const Eigen::Vector2d m_img = centroid(W, H, u, v, 60, [&](int x, int y) {
      const uint8_t* px = &img[(y * W + x) * 3];
      return px[0] != sky[0] || px[1] != sky[1] || px[2] != sky[2];
    }, &n_img);
    const Eigen::Vector2d m_depth = centroid(W, H, u, v, 60, [&](int x, int y) {
      return std::isfinite(cam.depth()[y * W + x]);
    }, &n_depth);
    EXPECT_GT(n_img, 300);
    EXPECT_EQ(n_img, n_depth);  // colour and depth from one pass: the same pixels
    EXPECT_NEAR(m_img.x(), u, 0.1) << p.transpose();
    EXPECT_NEAR(m_img.y(), v, 0.1) << p.transpose();
    EXPECT_NEAR(m_depth.x(), u, 0.1) << p.transpose();
    EXPECT_NEAR(m_depth.y(), v, 0.1) << p.transpose();
    // The cloud's points of the disc average to its centre (a disc is symmetric about it).
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int n = 0;
    for (int y = 0; y < H; ++y) {
      for (int x = 0; x < W; ++x) {
        float xyz[3];
        std::memcpy(xyz, &cam.cloud()[(y * W + x) * CloudLayout::kPointStep], sizeof(xyz));
        if (!std::isfinite(xyz[2]) || std::fabs(xyz[2] - z) > 0.01) continue;
        if ((Eigen::Vector3d(xyz[0], xyz[1], xyz[2]) - Eigen::Vector3d(p.x(), p.y(), z)).norm() > 0.3) continue;
        sum += Eigen::Vector3d(xyz[0], xyz[1], xyz[2]);
        ++n;
      }
    }
    ASSERT_GT(n, 300);
    EXPECT_NEAR(sum.x() / n, p.x(), 0.1 * z / info.K[0]) << p.transpose();  // 0.1 px at z
    EXPECT_NEAR(sum.y() / n, p.y(), 0.1 * z / info.K[4]) << p.transpose();
  }
}

// What depth_image_proc (point_cloud_xyz) and every perception stack do with depth + camera_info.
TEST(RenderPrincipalPoint, CloudIsTheStandardPinholeCloudOfDepthAndCameraInfo) {
  Renderer renderer;
  DepthCameraSensor cam(parseDepthCameraConfig(seedRealSense()), renderer);
  Scene scene = wallScene(2.0, "Gazebo/Red");
  scene.items[0].X_BS = Eigen::Translation3d(2.0, 0, 0) *
                        Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                        Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()) * Eigen::Translation3d(0.1, 0, 0);
  cam.render(scene, Eigen::Isometry3d::Identity());
  const CameraInfo& info = cam.info();
  const double fx = info.K[0], fy = info.K[4], cx = info.K[2], cy = info.K[5];
  double worst = 0.0;
  int finite = 0;
  for (int v = 0; v < info.height; ++v) {
    for (int u = 0; u < info.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v) * info.width + u;
      const double d = cam.depth()[i];
      float xyz[3];
      std::memcpy(xyz, &cam.cloud()[i * CloudLayout::kPointStep], sizeof(xyz));
      if (!std::isfinite(d)) {
        EXPECT_TRUE(std::isnan(xyz[0]) && std::isnan(xyz[1]) && std::isnan(xyz[2]));
        continue;
      }
      ++finite;
      const Eigen::Vector3d expected(d * (u - cx) / fx, d * (v - cy) / fy, d);
      worst = std::max(worst, (expected - Eigen::Vector3d(xyz[0], xyz[1], xyz[2])).norm());
    }
  }
  EXPECT_GT(finite, 640 * 480 / 2);
  EXPECT_LT(worst, 1e-4);  // 0.1 mm
}

// --- Image formats ---------------------------------------------------------------------------

// Coloured boxes in front of a coloured sky: every channel differs somewhere.
Scene colourfulScene() {
  Scene scene = wallScene(4.0, "Gazebo/Blue");
  scene.sky = Eigen::Vector4f(0.9f, 0.3f, 0.1f, 1.0f);
  scene.items[0].shape.size = Eigen::Vector3d(0.2, 2.0, 2.0);
  for (const auto& m : {std::make_pair("Gazebo/Red", -0.6), std::make_pair("Gazebo/Green", 0.6)}) {
    SceneItem item = scene.items[0];
    item.shape.size = Eigen::Vector3d(0.5, 0.5, 0.5);
    item.X_BS.translation() = Eigen::Vector3d(2.0, m.second, 0.2);
    item.material = findGazeboMaterial(m.first)->material;
    scene.items.push_back(item);
  }
  return scene;
}

CameraConfig formatCamera(const std::string& format, bool noise) {
  CameraConfig c = parseCameraConfig(edited(seedCamera(), "<format>R8G8B8", "<format>" + format));
  c.width = 96;
  c.height = 72;
  c.noise = noise;
  return c;
}

TEST(RenderImageFormats, Bgr8IsRgb8WithRedAndBlueSwapped) {
  Renderer renderer;
  const Scene scene = colourfulScene();
  for (bool noise : {false, true}) {
    CameraSensor rgb(formatCamera("R8G8B8", noise), renderer);
    CameraSensor bgr(formatCamera("B8G8R8", noise), renderer);
    rgb.render(scene, Eigen::Isometry3d::Identity());
    bgr.render(scene, Eigen::Isometry3d::Identity());
    EXPECT_STREQ(bgr.encoding(), "bgr8");
    ASSERT_EQ(bgr.image().size(), rgb.image().size());
    std::size_t differing_rb = 0;
    for (std::size_t i = 0; i < rgb.image().size(); i += 3) {
      ASSERT_EQ(bgr.image()[i], rgb.image()[i + 2]) << "pixel " << i / 3;
      ASSERT_EQ(bgr.image()[i + 1], rgb.image()[i + 1]) << "pixel " << i / 3;
      ASSERT_EQ(bgr.image()[i + 2], rgb.image()[i]) << "pixel " << i / 3;
      differing_rb += rgb.image()[i] != rgb.image()[i + 2];
    }
    EXPECT_GT(differing_rb, rgb.image().size() / 6);  // the swap is visible
  }
}

TEST(RenderImageFormats, Mono8AndMono16AreRec601Luma) {
  Renderer renderer;
  const Scene scene = colourfulScene();
  CameraSensor rgb(formatCamera("R8G8B8", false), renderer);
  CameraSensor mono8(formatCamera("L8", false), renderer);
  CameraSensor mono16(formatCamera("L16", false), renderer);
  rgb.render(scene, Eigen::Isometry3d::Identity());
  mono8.render(scene, Eigen::Isometry3d::Identity());
  mono16.render(scene, Eigen::Isometry3d::Identity());
  EXPECT_STREQ(mono8.encoding(), "mono8");
  EXPECT_STREQ(mono16.encoding(), "mono16");
  const std::size_t pixels = 96 * 72;
  ASSERT_EQ(mono8.image().size(), pixels);
  ASSERT_EQ(mono16.image().size(), 2 * pixels);
  std::set<int> values;
  for (std::size_t i = 0; i < pixels; ++i) {
    const uint8_t* p = &rgb.image()[3 * i];
    const double y = 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
    EXPECT_EQ(mono8.image()[i], static_cast<int>(std::lround(y))) << "pixel " << i;
    const int y16 = mono16.image()[2 * i] | (mono16.image()[2 * i + 1] << 8);  // little-endian
    EXPECT_EQ(y16, static_cast<int>(std::lround(y * 65535.0 / 255.0))) << "pixel " << i;
    values.insert(mono8.image()[i]);
  }
  EXPECT_GE(values.size(), 3u);
  // Full scale: white is 65535.
  Scene white;
  white.sky = Eigen::Vector4f(1, 1, 1, 1);
  mono16.render(white, Eigen::Isometry3d::Identity());
  EXPECT_EQ(mono16.image()[0] | (mono16.image()[1] << 8), 65535);
}

TEST(RenderImageFormats, DepthCameraFormatsAndTheDepthCameraPlugin) {
  // libgazebo_ros_depth_camera.so is read as openni_kinect: same topics, same outputs.
  SensorSpec spec = seedRealSense();
  spec.plugins[0].filename = "libgazebo_ros_depth_camera.so";
  const DepthCameraConfig a = parseDepthCameraConfig(seedRealSense());
  const DepthCameraConfig b = parseDepthCameraConfig(spec);
  EXPECT_TRUE(b.camera.has_plugin);
  EXPECT_EQ(b.depth_image_topic, a.depth_image_topic);
  EXPECT_EQ(b.point_cloud_topic, a.point_cloud_topic);
  EXPECT_EQ(b.camera.image_topic, a.camera.image_topic);
  EXPECT_EQ(b.camera.camera_info_topic, a.camera.camera_info_topic);
  EXPECT_EQ(b.depth_camera_info_topic, a.depth_camera_info_topic);
  // A bgr8 depth camera: image swapped, cloud colours still 0x00RRGGBB.
  Renderer renderer;
  DepthCameraConfig rgb_cfg = smallDepthConfig(), bgr_cfg = smallDepthConfig();
  bgr_cfg.camera.format = ImageFormat::kB8G8R8;
  DepthCameraSensor rgb(rgb_cfg, renderer), bgr(bgr_cfg, renderer);
  rgb.render(colourfulScene(), Eigen::Isometry3d::Identity());
  bgr.render(colourfulScene(), Eigen::Isometry3d::Identity());
  for (std::size_t i = 0; i < rgb.image().size(); i += 3) {
    ASSERT_EQ(bgr.image()[i], rgb.image()[i + 2]);
    ASSERT_EQ(bgr.image()[i + 2], rgb.image()[i]);
  }
  EXPECT_EQ(rgb.cloud(), bgr.cloud());
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
