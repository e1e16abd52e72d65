// Gazebo's wideanglecamera (gazebo/rendering/WideAngleCamera.cc, wide_lens_map_fp.glsl): the
// lens functions against their textbook formulas, the pixel <-> direction map, a rendered
// marker at a known angle landing where the lens puts it (beyond a pinhole's reach, and behind
// the camera's plane for a 200-degree lens), the cut-off, and bad <lens> input.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/plugins/camera/wide_angle_lens.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

std::string wideXml(const std::string& hfov, const std::string& lens, int width = 320,
                    int height = 240) {
  return "<sensor type='wideanglecamera' name='cam'><update_rate>30</update_rate><camera>"
         "<horizontal_fov>" + hfov + "</horizontal_fov><image><width>" + std::to_string(width) +
         "</width><height>" + std::to_string(height) + "</height></image><clip><near>0.05</near>"
         "<far>50</far></clip>" + lens + "</camera><plugin name='c' "
         "filename='libgazebo_ros_camera.so'><cameraName>camera</cameraName></plugin></sensor>";
}

SensorSpec spec(const std::string& xml) {
  SensorSpec s;
  s.name = "cam";
  s.type = "wideanglecamera";
  s.link = "camera_link";
  s.xml = xml;
  s.source = "autorace.urdf";
  s.line = 42;
  s.update_rate = 30;
  PluginSpec plugin;
  plugin.name = "c";
  plugin.filename = "libgazebo_ros_camera.so";
  plugin.params["cameraName"] = "camera";
  s.plugins.push_back(plugin);
  return s;
}

std::string errorOf(const std::string& xml) {
  return test::errorText<CameraError>([&] { parseCameraConfig(spec(xml)); }, "(no error)");
}

TEST(WideAngleLens, NamedTypesAreTheTextbookMappings) {
  // r = f g(theta) (https://en.wikipedia.org/wiki/Fisheye_lens#Mapping_function).
  struct Case {
    const char* type;
    double (*g)(double);
  };
  const Case cases[] = {{"gnomonical", [](double t) { return std::tan(t); }},
                        {"stereographic", [](double t) { return 2 * std::tan(t / 2); }},
                        {"equidistant", [](double t) { return t; }},
                        {"equisolid_angle", [](double t) { return 2 * std::sin(t / 2); }},
                        {"orthographic", [](double t) { return std::sin(t); }}};
  for (const Case& c : cases) {
    std::optional<WideAngleLens> lens = WideAngleLens::ofType(c.type);
    ASSERT_TRUE(lens) << c.type;
    lens->scale_to_hfov = false;
    lens->f = 1.3;
    for (double t = 0.05; t < 1.2; t += 0.1) {
      EXPECT_NEAR(lens->radius(t, 2.0), 1.3 * c.g(t), 1e-12) << c.type << " " << t;
      EXPECT_NEAR(lens->theta(lens->radius(t, 2.0), 2.0), t, 1e-12) << c.type;
    }
    // scale_to_hfov: theta = hfov/2 lands at the image's side edge (r = 1).
    lens->scale_to_hfov = true;
    EXPECT_NEAR(lens->radius(1.4 / 2, 1.4), 1.0, 1e-12) << c.type;
    EXPECT_NEAR(lens->focal(1.4), 1.0 / c.g(0.7), 1e-12) << c.type;
  }
  EXPECT_FALSE(WideAngleLens::ofType("fisheye"));
  EXPECT_FALSE(WideAngleLens::ofType("custom"));  // its constants come from <custom_function>
  // Orthographic has no angle beyond r = c1 f.
  WideAngleLens ortho = *WideAngleLens::ofType("orthographic");
  ortho.scale_to_hfov = false;
  EXPECT_TRUE(std::isnan(ortho.theta(1.01, 2.0)));
}

TEST(WideAngleLens, CustomFunctionAndCameraConfig) {
  // TurtleBot3's autorace camera (turtlebot3_description/urdf/
  // turtlebot3_burger_for_autorace_2020.gazebo.xacro): hfov 3.183, custom tan lens.
  const std::string lens =
      "<lens><type>custom</type><custom_function><c1>1.05</c1><c2>4</c2><f>1.0</f>"
      "<fun>tan</fun></custom_function><scale_to_hfov>true</scale_to_hfov>"
      "<cutoff_angle>3.1415</cutoff_angle><env_texture_size>512</env_texture_size></lens>";
  const CameraConfig c = parseCameraConfig(spec(wideXml("3.183", lens)));
  ASSERT_TRUE(c.wide_angle);
  EXPECT_EQ(c.lens.type, "custom");
  EXPECT_EQ(c.lens.fun, WideAngleLens::Fun::kTan);
  EXPECT_DOUBLE_EQ(c.lens.c1, 1.05);
  EXPECT_DOUBLE_EQ(c.lens.c2, 4.0);
  EXPECT_DOUBLE_EQ(c.lens.c3, 0.0);
  EXPECT_DOUBLE_EQ(c.lens.cutoff_angle, 3.1415);
  EXPECT_EQ(c.lens.env_texture_size, 512);
  for (double t = 0.1; t < 1.5; t += 0.2) {
    const double f = 1.0 / (1.05 * std::tan(3.183 / 2 / 4));
    EXPECT_NEAR(c.lens.radius(t, c.horizontal_fov), 1.05 * f * std::tan(t / 4), 1e-12);
  }
  // camera_info is gazebo_ros_camera_utils's pinhole K, f = W / (2 tan(hfov / 2)): negative
  // beyond 180 degrees, as there.
  EXPECT_NEAR(makeCameraInfo(c).K[0], 320 / (2 * std::tan(3.183 / 2)), 1e-9);
  EXPECT_LT(makeCameraInfo(c).K[0], 0.0);
  // No <lens>: camera.sdf's defaults (stereographic, scale_to_hfov, cutoff 1.5707, 256).
  const CameraConfig d = parseCameraConfig(spec(wideXml("2.0", "")));
  EXPECT_EQ(d.lens.type, "stereographic");
  EXPECT_TRUE(d.lens.scale_to_hfov);
  EXPECT_DOUBLE_EQ(d.lens.cutoff_angle, 1.5707);
  EXPECT_EQ(d.lens.env_texture_size, 256);
  // The kind is gazebo_ros_camera's: image_raw and camera_info under the camera's name.
  const SensorSpec s = spec(wideXml("2.0", ""));
  ASSERT_NE(findSensorKind(s), nullptr);
  EXPECT_EQ(findSensorKind(s)->id, "camera");
  const std::vector<SensorTopic> topics = sensorTopics(s, "turtlebot3_burger");
  ASSERT_EQ(topics.size(), 2u);
  EXPECT_EQ(topics[0].topic, "/camera/image_raw");
  EXPECT_EQ(topics[1].topic, "/camera/camera_info");
}

TEST(WideAngleMap, PixelsLookWhereTheLensSays) {
  WideAngleLens lens = *WideAngleLens::ofType("equidistant");
  const WideAngleMap map(lens, 3.0, 320, 240);
  double r = 0;
  // Just right of the centre: nearly forward, a little to the right (-y).
  const Eigen::Vector3d right = map.direction(160, 119, &r);
  EXPECT_GT(right.x(), 0.99);
  EXPECT_LT(right.y(), 0.0);
  EXPECT_GT(right.z(), 0.0);  // row 119 is above the centre (119.5)
  // The right edge's pixel centre is at r = 1 - 1/320: theta = (hfov/2) r.
  const Eigen::Vector3d edge = map.direction(319, 120, &r);
  EXPECT_NEAR(r, std::hypot(1.0 - 1.0 / 320, 0.5 / 160), 1e-12);
  EXPECT_NEAR(std::acos(edge.x()), 1.5 * r, 1e-9);
  // project() inverts direction().
  for (int v = 3; v < 240; v += 37) {
    for (int u = 5; u < 320; u += 41) {
      double pu = 0, pv = 0;
      ASSERT_TRUE(map.project(map.direction(u, v), &pu, &pv));
      EXPECT_NEAR(pu, u, 1e-9);
      EXPECT_NEAR(pv, v, 1e-9);
    }
  }
}

// A red ball at `at` (camera link frame) on a grey sky.
Scene ballScene(const Eigen::Vector3d& at, double radius) {
  Scene scene;
  scene.sky = Eigen::Vector4f(0.5f, 0.5f, 0.5f, 1.0f);
  scene.lights.push_back(DirectionalLight{});
  scene.lights[0].direction = -at.normalized();
  scene.addBody(SceneBody{"ball::link", "ball", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.shape.type = ShapeType::kSphere;
  item.shape.radius = radius;
  item.X_BS.translation() = at;
  item.material = findGazeboMaterial("Gazebo/Red")->material;
  scene.items.push_back(item);
  return scene;
}

Eigen::Vector2d redCentroid(const CameraSensor& cam, int* count) {
  const CameraConfig& c = cam.config();
  Eigen::Vector2d sum(0, 0);
  int n = 0;
  for (int v = 0; v < c.height; ++v) {
    for (int u = 0; u < c.width; ++u) {
      const uint8_t* p = &cam.image()[(static_cast<std::size_t>(v) * c.width + u) * 3];
      if (p[0] > 2 * p[1] + 20) {
        sum += Eigen::Vector2d(u, v);
        ++n;
      }
    }
  }
  *count = n;
  return n ? Eigen::Vector2d(sum / n) : sum;
}

TEST(WideAngleRender, AMarkerLandsWhereTheLensPutsIt) {
  Renderer renderer;
  struct Case {
    std::string hfov, lens;
    Eigen::Vector3d at;
  };
  const Case cases[] = {
      // About 60 degrees left and 10 up of the axis.
      {"3.0", "<lens><type>equidistant</type><cutoff_angle>3.14</cutoff_angle></lens>",
       Eigen::Vector3d(std::cos(1.05), std::sin(1.05), 0.35).normalized() * 2.0},
      {"2.6", "<lens><type>stereographic</type><env_texture_size>384</env_texture_size></lens>",
       Eigen::Vector3d(1.0, -0.9, -0.6).normalized() * 2.0},
      // 200 degrees: a marker 95 degrees off the axis, behind the camera's plane.
      {"3.4907", "<lens><type>equisolid_angle</type><cutoff_angle>1.75</cutoff_angle></lens>",
       Eigen::Vector3d(std::cos(1.658), std::sin(1.658), 0.0) * 2.0},
      {"2.0", "<lens><type>custom</type><custom_function><c1>1.05</c1><c2>4</c2><f>1</f>"
              "<fun>tan</fun></custom_function><cutoff_angle>3.14</cutoff_angle></lens>",
       Eigen::Vector3d(2.0, 0.5, -0.4)},
  };
  for (const Case& c : cases) {
    CameraSensor cam(parseCameraConfig(spec(wideXml(c.hfov, c.lens))), renderer);
    cam.render(ballScene(c.at, 0.12), Eigen::Isometry3d::Identity());
    WideAngleMap map(cam.config().lens, cam.config().horizontal_fov, 320, 240);
    double u = 0, v = 0;
    ASSERT_TRUE(map.project(c.at, &u, &v));
    int n = 0;
    const Eigen::Vector2d seen = redCentroid(cam, &n);
    EXPECT_GT(n, 15) << c.lens;
    EXPECT_NEAR(seen.x(), u, 1.0) << c.lens;
    EXPECT_NEAR(seen.y(), v, 1.0) << c.lens;
  }
}

TEST(WideAngleRender, BeyondTheCutoffIsBlack) {
  Renderer renderer;
  CameraSensor cam(parseCameraConfig(spec(wideXml(
                       "3.0", "<lens><type>equidistant</type><cutoff_angle>1.0</cutoff_angle>"
                              "</lens>"))),
                   renderer);
  cam.render(ballScene(Eigen::Vector3d(3, 0, 0), 0.1), Eigen::Isometry3d::Identity());
  const WideAngleLens& lens = cam.config().lens;
  const double cut = lens.cutRadius(3.0);  // 1.0 / 1.5
  EXPECT_NEAR(cut, 1.0 / 1.5, 1e-12);
  WideAngleMap map(lens, 3.0, 320, 240);
  int black_out = 0, outside = 0, lit_in = 0, inside = 0;
  for (int v = 0; v < 240; ++v) {
    for (int u = 0; u < 320; ++u) {
      double r = 0;
      map.direction(u, v, &r);
      const uint8_t* p = &cam.image()[(static_cast<std::size_t>(v) * 320 + u) * 3];
      const bool black = p[0] == 0 && p[1] == 0 && p[2] == 0;
      if (r >= cut) {
        ++outside;
        black_out += black;
      } else if (r < cut - 0.02) {
        ++inside;
        lit_in += !black;
      }
    }
  }
  EXPECT_GT(outside, 10000);
  EXPECT_EQ(black_out, outside);
  EXPECT_GT(inside, 10000);
  EXPECT_EQ(lit_in, inside);
}

TEST(WideAngleRender, AShapeThatChangesSizeIsDrawnAtItsNewSize) {
  // The renderer matches items by index and shape kind and draws primitives at their current
  // size: a ball that grows between two frames covers more of the image (the ray caster's
  // side: RayCaster.AShapeThatChangesSizeOrIsSwappedForAnotherIsRebuilt).
  Renderer renderer;
  CameraSensor cam(parseCameraConfig(spec(wideXml("2.0", "<lens><type>equidistant</type>"
                                                          "<cutoff_angle>3.1</cutoff_angle></lens>"))),
                   renderer);
  Scene scene = ballScene(Eigen::Vector3d(3, 0, 0), 0.1);
  int small = 0, large = 0;
  cam.render(scene, Eigen::Isometry3d::Identity());
  redCentroid(cam, &small);
  scene.items[0].shape.radius = 0.3;
  cam.render(scene, Eigen::Isometry3d::Identity());
  redCentroid(cam, &large);
  EXPECT_GT(small, 10);
  EXPECT_NEAR(static_cast<double>(large) / small, 9.0, 1.5);  // area ~ radius^2
}

TEST(WideAngleConfig, BadLensIsAnErrorAtTheSensorNamingTheValue) {
  const std::string unknown = errorOf(wideXml("2.0", "<lens><type>fisheye</type></lens>"));
  EXPECT_NE(unknown.find("autorace.urdf:42:"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("<lens><type> 'fisheye'"), std::string::npos) << unknown;
  const std::string fun = errorOf(wideXml(
      "2.0", "<lens><type>custom</type><custom_function><fun>cos</fun></custom_function></lens>"));
  EXPECT_NE(fun.find("autorace.urdf:42:"), std::string::npos) << fun;
  EXPECT_NE(fun.find("<fun> 'cos' is not a lens function (sin, tan, id)"), std::string::npos) << fun;
  for (const std::string size : {"0", "-4"}) {
    const std::string e = errorOf(wideXml(
        "2.0", "<lens><type>equidistant</type><env_texture_size>" + size +
                   "</env_texture_size></lens>"));
    EXPECT_NE(e.find("autorace.urdf:42:"), std::string::npos) << e;
    EXPECT_NE(e.find("<lens><env_texture_size> " + size), std::string::npos) << e;
  }
  // A gnomonical lens cannot show 200 degrees (f = 1 / tan(100 deg) < 0).
  EXPECT_NE(errorOf(wideXml("3.4907", "<lens><type>gnomonical</type></lens>")).find("has no image"),
            std::string::npos);
  // The same values on a good lens load.
  EXPECT_EQ(errorOf(wideXml("2.0", "<lens><type>equidistant</type><env_texture_size>64"
                                   "</env_texture_size></lens>")),
            "(no error)");
}

}  // namespace
}  // namespace tianracer_sim
