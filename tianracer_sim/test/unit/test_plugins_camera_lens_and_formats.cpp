// Gazebo's lens distortion (<camera><distortion>, gazebo_ros's autoDistortion / borderCrop) and
// the image formats R16G16B16 and BAYER_*: the model and its inverse, the pixel map against
// the model, the crop, where a distorted image puts a known point, and the format conversions
// against the rgb8 image of the same scene.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <tinyxml2.h>

#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/lens_distortion.h"
#include "tianracer_sim/scene/materials.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

// gazebo_ros_pkgs' distortion worlds' camera (f = W: hfov = 2 atan(1/2)), smaller.
std::string cameraXml(const std::string& format, const std::string& distortion,
                      const std::string& plugin_extra) {
  return "<sensor type='camera' name='cam'><update_rate>30</update_rate><camera name='head'>"
         "<horizontal_fov>0.927295218</horizontal_fov><image><width>200</width><height>160"
         "</height><format>" + format + "</format></image><clip><near>0.02</near><far>300</far>"
         "</clip>" + distortion + "</camera><plugin name='c' filename='libgazebo_ros_camera.so'>"
         "<cameraName>cam</cameraName>" + plugin_extra + "</plugin></sensor>";
}

SensorSpec spec(const std::string& xml) {
  tinyxml2::XMLDocument doc;
  EXPECT_EQ(doc.Parse(xml.c_str()), tinyxml2::XML_SUCCESS) << xml;
  SensorSpec s;
  s.name = "cam";
  s.type = "camera";
  s.link = "camera_link";
  s.xml = xml;
  s.source = "distortion.world";
  s.line = 20;
  s.update_rate = 30;
  const auto* p = doc.RootElement()->FirstChildElement("plugin");
  PluginSpec plugin;
  plugin.name = p->Attribute("name");
  plugin.filename = p->Attribute("filename");
  for (const auto* e = p->FirstChildElement(); e; e = e->NextSiblingElement())
    plugin.params[e->Name()] = e->GetText() ? e->GetText() : "";
  s.plugins.push_back(plugin);
  return s;
}

const std::string kBarrel =
    "<distortion><k1>-0.1</k1><k2>-0.1</k2><p1>0</p1><p2>0</p2><k3>-0.1</k3>"
    "<center>0.5 0.5</center></distortion>";

std::string errorOf(const std::string& xml) {
  return test::errorText<CameraError>([&] { parseCameraConfig(spec(xml)); }, "(no error)");
}

TEST(LensDistortionModel, BrownsModelAndItsInverse) {
  LensDistortion d;
  d.k1 = -0.1;
  d.k2 = -0.1;
  d.k3 = -0.1;
  const Eigen::Vector2d x(0.3, -0.2);
  const double r2 = 0.13, radial = 1 - 0.1 * r2 - 0.1 * r2 * r2 - 0.1 * r2 * r2 * r2;
  EXPECT_TRUE(distortNormalized(d, x).isApprox(x * radial, 1e-12));
  d.p1 = 0.01;
  d.p2 = -0.02;
  const Eigen::Vector2d xd = distortNormalized(d, x);
  EXPECT_NEAR(xd.x(), 0.3 * radial + 2 * 0.01 * 0.3 * -0.2 + -0.02 * (r2 + 2 * 0.09), 1e-12);
  EXPECT_NEAR(xd.y(), -0.2 * radial + 0.01 * (r2 + 2 * 0.04) + 2 * -0.02 * 0.3 * -0.2, 1e-12);
  for (const double k : {-0.1, 0.1}) {  // barrel, pincushion
    LensDistortion e;
    e.k1 = e.k2 = e.k3 = k;
    e.p1 = 0.005;
    for (double u = -0.6; u <= 0.6; u += 0.15) {
      for (double v = -0.5; v <= 0.5; v += 0.125) {
        Eigen::Vector2d back;
        ASSERT_TRUE(undistortNormalized(e, distortNormalized(e, {u, v}), &back)) << u << " " << v;
        EXPECT_NEAR(back.x(), u, 1e-9);
        EXPECT_NEAR(back.y(), v, 1e-9);
      }
    }
  }
  // Strong barrel folds over beyond its maximum radius: no undistorted point lands there.
  LensDistortion strong;
  strong.k1 = -1.0;
  Eigen::Vector2d none;
  EXPECT_FALSE(undistortNormalized(strong, {0.5, 0.0}, &none));  // max of r (1 - r^2) is 0.385
}

CameraIntrinsics intrinsics() {
  CameraIntrinsics k;
  k.width = 200;
  k.height = 160;
  k.fx = k.fy = 200.0;
  k.cx = 100.5;
  k.cy = 80.5;
  return k;
}

TEST(LensDistortionMap, EveryOutputPixelShowsThePointThatLandsThere) {
  const CameraIntrinsics k = intrinsics();
  for (const double k1 : {-0.1, 0.1}) {
    LensDistortion d;
    d.k1 = d.k2 = d.k3 = k1;
    d.p2 = 0.003;
    const DistortionMap map(d, k);
    EXPECT_EQ(map.scale(), Eigen::Vector2d(1, 1));
    int black = 0;
    for (int v = 0; v < k.height; ++v) {
      for (int u = 0; u < k.width; ++u) {
        const Eigen::Vector2f s = map.source(u, v);
        if (std::isnan(s.x())) {
          ++black;
          continue;
        }
        const Eigen::Vector2d x((s.x() - k.cx) / k.fx, (s.y() - k.cy) / k.fy);
        const Eigen::Vector2d p = distortNormalized(d, x) * k.fx + Eigen::Vector2d(k.cx, k.cy);
        ASSERT_NEAR(p.x(), u, 1e-3) << u << " " << v;
        ASSERT_NEAR(p.y(), v, 1e-3) << u << " " << v;
      }
    }
    // Barrel shows black only in the corners (there the undistorted point is off the image);
    // pincushion shows the middle of the rendered image, no black.
    if (k1 < 0) {
      EXPECT_GT(black, 0);
      EXPECT_TRUE(std::isnan(map.source(0, 0).x()));
      EXPECT_FALSE(std::isnan(map.source(100, 10).x()));
    } else {
      EXPECT_EQ(black, 0);
    }
  }
}

TEST(LensDistortionMap, CropScalesTheDistortedFrameOverTheImage) {
  const CameraIntrinsics k = intrinsics();
  LensDistortion d;
  d.k1 = d.k2 = d.k3 = -0.1;
  d.crop = true;
  const DistortionMap map(d, k);
  EXPECT_LT(map.scale().x(), 1.0);
  EXPECT_LT(map.scale().y(), 1.0);
  for (int v = 0; v < k.height; ++v) {
    for (int u = 0; u < k.width; ++u) ASSERT_FALSE(std::isnan(map.source(u, v).x())) << u << " " << v;
  }
  // The corner pixel shows (nearly) the rendered corner: the frame's distorted corner.
  EXPECT_NEAR(map.source(0, 0).x(), 0.0, 1.0);
  EXPECT_NEAR(map.source(0, 0).y(), 0.0, 1.0);
  // Pincushion is never cropped (Gazebo: crop only for k1 < 0).
  d.k1 = d.k2 = d.k3 = 0.1;
  EXPECT_EQ(DistortionMap(d, k).scale(), Eigen::Vector2d(1, 1));
}

TEST(LensDistortionConfig, DistortionElementAutoDistortionAndBorderCrop) {
  CameraConfig c = parseCameraConfig(spec(cameraXml(
      "R8G8B8", kBarrel, "<autoDistortion>true</autoDistortion><borderCrop>false</borderCrop>")));
  EXPECT_DOUBLE_EQ(c.distortion.k1, -0.1);
  EXPECT_DOUBLE_EQ(c.distortion.k3, -0.1);
  EXPECT_TRUE(c.distortion.enabled());
  EXPECT_FALSE(c.distortion.crop);  // borderCrop false
  EXPECT_EQ(makeCameraInfo(c).D, (std::array<double, 5>{-0.1, -0.1, 0, 0, -0.1}));
  // borderCrop defaults to true: barrel is cropped.
  c = parseCameraConfig(spec(cameraXml("R8G8B8", kBarrel, "<autoDistortion>1</autoDistortion>")));
  EXPECT_TRUE(c.distortion.crop);
  // Without autoDistortion, D is the plugin's distortionK1.. (pincushion world), and a D that
  // differs from the distortion applied is reported.
  std::vector<std::string> warnings;
  const std::string pincushion =
      "<distortion><k1>0.1</k1><k2>0.1</k2><p1>0</p1><p2>0</p2><k3>0.1</k3>"
      "<center>0.5 0.5</center></distortion>";
  c = parseCameraConfig(spec(cameraXml("R8G8B8", pincushion,
                                       "<distortionK1>0.1</distortionK1><distortionK2>0.1"
                                       "</distortionK2><distortionK3>0.1</distortionK3>")),
                        [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_FALSE(c.distortion.crop);
  EXPECT_EQ(makeCameraInfo(c).D, (std::array<double, 5>{0.1, 0.1, 0, 0, 0.1}));
  c = parseCameraConfig(spec(cameraXml("R8G8B8", pincushion, "")),
                        [&](const std::string& w) { warnings.push_back(w); });
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("camera_info D [0 0 0 0 0] differs from the <distortion>"),
            std::string::npos) << warnings[0];
  // Bad input names the sensor, the element and the value.
  std::string e = errorOf(cameraXml("R8G8B8", "<distortion><k1>big</k1></distortion>", ""));
  EXPECT_NE(e.find("distortion.world:20: camera sensor 'cam'"), std::string::npos) << e;
  EXPECT_NE(e.find("<distortion><k1> 'big' is not a number"), std::string::npos) << e;
  e = errorOf(cameraXml("R8G8B8", "<distortion><center>0.5</center></distortion>", ""));
  EXPECT_NE(e.find("<distortion><center> '0.5' is not two numbers"), std::string::npos) << e;
  e = errorOf(cameraXml("R8G8B8", kBarrel, "<borderCrop>maybe</borderCrop>"));
  EXPECT_NE(e.find("<borderCrop> 'maybe' is not a boolean"), std::string::npos) << e;
}

// A small red cube off the axis of a camera at the origin looking along x, on grey.
Scene cubeScene(const Eigen::Vector3d& at) {
  Scene scene;
  scene.sky = Eigen::Vector4f(0.5f, 0.5f, 0.5f, 1.0f);
  scene.lights.push_back(DirectionalLight{});
  scene.lights[0].direction = Eigen::Vector3d(1, 0, -0.2).normalized();
  scene.addBody(SceneBody{"cube::link", "cube", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.shape.type = ShapeType::kBox;
  item.shape.size = Eigen::Vector3d(0.02, 0.12, 0.12);
  item.X_BS.translation() = at;
  item.material = findGazeboMaterial("Gazebo/Red")->material;
  scene.items.push_back(item);
  return scene;
}

Eigen::Vector2d redCentroid(const CameraSensor& cam) {
  const CameraConfig& c = cam.config();
  Eigen::Vector2d sum(0, 0);
  double n = 0;
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) {
      const uint8_t* p = &cam.image()[(static_cast<std::size_t>(v) * c.width + u) * 3];
      if (p[0] > 2 * p[1] + 20) {
        sum += Eigen::Vector2d(u, v);
        ++n;
      }
    }
  }
  EXPECT_GT(n, 20);
  return sum / n;
}

TEST(LensDistortionRender, TheDistortedImageShowsAPointWhereTheModelPutsIt) {
  Renderer renderer;
  const Eigen::Vector3d at(2.0, 0.8, 0.6);  // link frame: x forward, y left, z up
  const Scene scene = cubeScene(at);
  CameraSensor plain(parseCameraConfig(spec(cameraXml("R8G8B8", "", ""))), renderer);
  plain.render(scene, Eigen::Isometry3d::Identity());
  const CameraInfo info = plain.info();
  const double f = info.K[0], cx = info.K[2], cy = info.K[5];
  const Eigen::Vector2d x(-at.y() / at.x(), -at.z() / at.x());  // optical: x right, y down
  const Eigen::Vector2d undistorted = redCentroid(plain);
  EXPECT_NEAR(undistorted.x(), cx + f * x.x(), 0.5);
  EXPECT_NEAR(undistorted.y(), cy + f * x.y(), 0.5);
  for (const std::string k : {"-0.1", "0.1"}) {
    const std::string d = "<distortion><k1>" + k + "</k1><k2>" + k + "</k2><k3>" + k +
                          "</k3><p1>0.01</p1><p2>0</p2><center>0.5 0.5</center></distortion>";
    CameraSensor lens(parseCameraConfig(spec(cameraXml(
                          "R8G8B8", d, "<autoDistortion>true</autoDistortion>"
                                       "<borderCrop>false</borderCrop>"))),
                      renderer);
    lens.render(scene, Eigen::Isometry3d::Identity());
    LensDistortion model = lens.config().distortion;
    const Eigen::Vector2d xd = distortNormalized(model, x);
    const Eigen::Vector2d seen = redCentroid(lens);
    EXPECT_NEAR(seen.x(), cx + f * xd.x(), 0.6) << "k = " << k;
    EXPECT_NEAR(seen.y(), cy + f * xd.y(), 0.6) << "k = " << k;
    EXPECT_GT((seen - undistorted).norm(), 2.0) << "k = " << k;  // the lens moved it
    // OpenCV's plumb_bob with the published D is this model.
    EXPECT_EQ(lens.info().D, (std::array<double, 5>{std::stod(k), std::stod(k), 0.01, 0, std::stod(k)}));
  }
}

TEST(ImageFormats, Rgb16IsRgb8Times257AndBayerKeepsThePatternsChannel) {
  Renderer renderer;
  const Scene scene = cubeScene({2.0, 0.1, 0.05});
  CameraSensor rgb(parseCameraConfig(spec(cameraXml("R8G8B8", "", ""))), renderer);
  rgb.render(scene, Eigen::Isometry3d::Identity());
  const std::size_t pixels = 200 * 160;
  CameraSensor rgb16(parseCameraConfig(spec(cameraXml("R16G16B16", "", ""))), renderer);
  rgb16.render(scene, Eigen::Isometry3d::Identity());
  EXPECT_STREQ(rgb16.encoding(), "rgb16");
  EXPECT_EQ(rgb16.bytesPerPixel(), 6);
  EXPECT_EQ(rgb16.channels(), 3);
  ASSERT_EQ(rgb16.image().size(), pixels * 6);
  for (std::size_t i = 0; i < pixels * 3; ++i) {
    const int v16 = rgb16.image()[2 * i] | (rgb16.image()[2 * i + 1] << 8);  // little-endian
    ASSERT_EQ(v16, rgb.image()[i] * 257) << "channel " << i;
  }
  const char* names[] = {"BAYER_RGGB8", "BAYER_BGGR8", "BAYER_GBRG8", "BAYER_GRBG8"};
  const char* encodings[] = {"bayer_rggb8", "bayer_bggr8", "bayer_gbrg8", "bayer_grbg8"};
  const char* tiles[] = {"RGGB", "BGGR", "GBRG", "GRBG"};
  for (int b = 0; b < 4; ++b) {
    CameraSensor bayer(parseCameraConfig(spec(cameraXml(names[b], "", ""))), renderer);
    bayer.render(scene, Eigen::Isometry3d::Identity());
    EXPECT_STREQ(bayer.encoding(), encodings[b]);
    EXPECT_EQ(bayer.bytesPerPixel(), 1);
    ASSERT_EQ(bayer.image().size(), pixels);
    for (int v = 0; v < 160; ++v) {
      for (int u = 0; u < 200; ++u) {
        const char c = tiles[b][(v % 2) * 2 + u % 2];
        const int channel = c == 'R' ? 0 : c == 'G' ? 1 : 2;
        const std::size_t i = static_cast<std::size_t>(v) * 200 + u;
        ASSERT_EQ(bayer.image()[i], rgb.image()[3 * i + channel]) << names[b] << " " << u << " " << v;
      }
    }
  }
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
