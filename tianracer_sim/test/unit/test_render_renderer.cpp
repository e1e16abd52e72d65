// Renderer against analytic answers: the lit colour of a flat face, depth along the optical
// axis, skipped meshes, determinism. Headless (OSMesa), no roscore.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tianracer_sim/scene/materials.h"
#include "tianracer_sim/render/renderer.h"

namespace tianracer_sim {
namespace {

// A scene with one static body holding a box whose front face (normal -x) is the plane
// x = distance, filling the view of a camera at the origin looking along +x.
Scene boxScene(double distance, const std::string& material, double tilt = 0.0) {
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  scene.lights[0].direction = Eigen::Vector3d(0.6, -0.3, -0.74);
  const int body = scene.addBody(SceneBody{"wall::link", "wall", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.body = body;
  item.shape.type = ShapeType::kBox;
  item.shape.size = Eigen::Vector3d(0.2, 400.0, 400.0);
  // Rotate about z by `tilt`: the face becomes x = distance + tan(tilt) * y.
  item.X_BS = Eigen::Translation3d(distance, 0, 0) * Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitZ()) *
              Eigen::Translation3d(0.1, 0, 0);
  item.material = findGazeboMaterial(material)->material;
  scene.items.push_back(item);
  return scene;
}

// The shading equation of the renderer (renderer.cpp) for the centre pixel of boxScene.
Eigen::Vector3d expectedCentreColour(const Scene& scene, const GazeboMaterial& m) {
  const Eigen::Vector3d n(-1, 0, 0), v(-1, 0, 0);
  Eigen::Vector3d c = scene.ambient.head<3>().cast<double>().cwiseProduct(m.material.ambient.head<3>().cast<double>());
  for (const auto& light : scene.lights) {
    const Eigen::Vector3d l = -light.direction.normalized();
    const double ndl = n.dot(l);
    if (ndl <= 0) continue;
    c += light.diffuse.head<3>().cast<double>().cwiseProduct(m.material.diffuse.head<3>().cast<double>()) * ndl;
    const Eigen::Vector3d h = (l + v).normalized();
    c += light.specular.head<3>().cast<double>().cwiseProduct(m.material.specular.head<3>().cast<double>()) *
         std::pow(std::max(n.dot(h), 0.0), std::max<double>(m.shininess, 1.0));
  }
  return c.cwiseMax(0.0).cwiseMin(1.0);
}

TEST(RenderRenderer, CentrePixelIsTheLitGazeboMaterial) {
  Renderer renderer;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(64, 48, 1.0, 0.05, 8.0);
  std::vector<uint8_t> rgb(64 * 48 * 3);
  // Tolerance: 2/255 (8-bit quantisation of a float shader result, llvmpipe rounding).
  for (const char* name : {"Gazebo/Red", "Gazebo/Grey", "Gazebo/DarkGrey", "Gazebo/Orange",
                           "Gazebo/Blue", "Gazebo/Yellow", "Gazebo/White", "Gazebo/Black"}) {
    const Scene scene = boxScene(1.0, name);
    renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, rgb.data());
    const Eigen::Vector3d want = 255.0 * expectedCentreColour(scene, *findGazeboMaterial(name));
    const uint8_t* px = &rgb[(24 * 64 + 32) * 3];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(px[c], want[c], 2.0) << name << " channel " << c;
    }
  }
}

// render_bench's cost table reads these: one draw per untextured item, the ground plane's two
// triangles last in its own program, and the flat probe draws the ambient product only (the
// probe is off again afterwards: the lit colour comes back).
TEST(RenderRenderer, FrameStatsAndTheFlatShadingProbe) {
  Renderer renderer;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(64, 48, 1.0, 0.05, 8.0);
  std::vector<uint8_t> rgb(64 * 48 * 3);
  Scene scene = boxScene(1.0, "Gazebo/Red");
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, rgb.data());
  EXPECT_EQ(renderer.lastFrameStats().draw_calls, 1);
  EXPECT_EQ(renderer.lastFrameStats().triangles, 12u);
  EXPECT_EQ(renderer.lastFrameStats().program_switches, 1);
  scene.ground_plane = true;
  scene.items.push_back(scene.items[0]);
  scene.items.back().X_BS.translation().y() += 1000.0;  // out of view: still drawn (no culling of items)
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, rgb.data());
  EXPECT_EQ(renderer.lastFrameStats().draw_calls, 3);
  EXPECT_EQ(renderer.lastFrameStats().triangles, 26u);
  EXPECT_EQ(renderer.lastFrameStats().program_switches, 2);

  const Scene box = boxScene(1.0, "Gazebo/Red");
  const GazeboMaterial red = *findGazeboMaterial("Gazebo/Red");  // returned by value
  const uint8_t* px = &rgb[(24 * 64 + 32) * 3];
  renderer.setFlatShadingProbe(true);
  renderer.renderView(box, Eigen::Isometry3d::Identity(), K, rgb.data());
  const Eigen::Vector3d flat =
      255.0 * box.ambient.head<3>().cast<double>().cwiseProduct(red.material.ambient.head<3>().cast<double>());
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(px[c], flat[c], 1.0) << "channel " << c;
  renderer.setFlatShadingProbe(false);
  renderer.renderView(box, Eigen::Isometry3d::Identity(), K, rgb.data());
  const Eigen::Vector3d lit = 255.0 * expectedCentreColour(box, red);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(px[c], lit[c], 2.0) << "channel " << c;
  EXPECT_GT(lit[0] - flat[0], 20.0) << "the probe's colour differs visibly from the lit one";
}

TEST(RenderRenderer, SkyWhereNothingIsHitAndDepthInfinite) {
  Renderer renderer;
  Scene scene;
  scene.sky = Eigen::Vector4f(0.2f, 0.4f, 0.6f, 1.0f);
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(16, 8, 1.0, 0.1, 10.0);
  std::vector<uint8_t> rgb(16 * 8 * 3);
  std::vector<float> depth(16 * 8, 0.0f);
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, rgb.data(), depth.data());
  for (int i = 0; i < 16 * 8; ++i) {
    EXPECT_NEAR(rgb[3 * i], 51, 1);
    EXPECT_NEAR(rgb[3 * i + 1], 102, 1);
    EXPECT_NEAR(rgb[3 * i + 2], 153, 1);
    EXPECT_TRUE(std::isinf(depth[i]));
  }
}

// Depth of every pixel of a tilted face against the analytic plane intersection:
// face x = d + a y (link frame), y = -Z (u - cx) / f -> optical Z = d / (1 + a (u - cx) / f).
double maxDepthError(Renderer* renderer, double distance, double near_clip, double far_clip,
                     double tilt, float* centre) {
  const int W = 160, H = 120;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(W, H, 1.0, near_clip, far_clip);
  const Scene scene = boxScene(distance, "Gazebo/Grey", tilt);
  std::vector<float> depth(W * H);
  renderer->renderView(scene, Eigen::Isometry3d::Identity(), K, nullptr, depth.data());
  const double a = -std::tan(tilt);  // the rotated face: x = d - tan(tilt) y
  double worst = 0.0;
  for (int v = 2; v < H - 2; ++v) {
    for (int u = 2; u < W - 2; ++u) {
      const double want = distance / (1.0 + a * (u - K.cx) / K.fx);
      worst = std::max(worst, std::fabs(depth[v * W + u] - want));
    }
  }
  *centre = 0.5f * (depth[(H / 2) * W + W / 2] + depth[(H / 2 - 1) * W + W / 2 - 1]);
  return worst;
}

TEST(RenderRenderer, DepthIsTheDistanceAlongTheOpticalAxis) {
  Renderer renderer;
  float centre = 0.0f;
  for (const auto& clip : {std::make_pair(0.05, 8.0), std::make_pair(0.02, 300.0)}) {
    const double at1 = maxDepthError(&renderer, 1.0, clip.first, clip.second, 0.0, &centre);
    EXPECT_NEAR(centre, 1.0, 1e-3);
    EXPECT_LT(at1, 1e-3) << "near " << clip.first << " far " << clip.second;
    const double at4 = maxDepthError(&renderer, 4.0, clip.first, clip.second, 0.0, &centre);
    EXPECT_NEAR(centre, 4.0, 1e-2);
    EXPECT_LT(at4, 1e-2) << "near " << clip.first << " far " << clip.second;
    // A face tilted by 0.4 rad: depth varies across the image, still analytic.
    const double tilted1 = maxDepthError(&renderer, 1.0, clip.first, clip.second, 0.4, &centre);
    const double tilted4 = maxDepthError(&renderer, 4.0, clip.first, clip.second, 0.4, &centre);
    EXPECT_LT(tilted1, 1e-3);
    EXPECT_LT(tilted4, 1e-2);
    std::printf("[ depth    ] near %.2f far %.0f: max |error| %.2e m at 1 m, %.2e m at 4 m; "
                "tilted %.2e / %.2e m\n", clip.first, clip.second, at1, at4, tilted1, tilted4);
  }
}

TEST(RenderRenderer, CameraPoseAndImageOrientation) {
  // A red box up and to the left of the optical axis must appear in the top-left quadrant.
  Renderer renderer;
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  const int body = scene.addBody(SceneBody{"b", "m", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.body = body;
  item.shape.type = ShapeType::kBox;
  item.shape.size = Eigen::Vector3d(0.3, 0.3, 0.3);
  item.X_BS.translation() = Eigen::Vector3d(3.0, 0.5, 0.4);  // forward, left, up (link frame)
  item.material = findGazeboMaterial("Gazebo/Red")->material;
  scene.items.push_back(item);
  scene.sky = Eigen::Vector4f(0, 0, 0, 1);
  // Camera at (10, 5, 1) yawed by 90 degrees: its "forward" is world +y.
  Eigen::Isometry3d X_WC = Eigen::Translation3d(10, 5, 1) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  scene.bodies[0].X_WB = X_WC;  // the box moves with the camera
  const int W = 100, H = 80;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(W, H, 1.2, 0.1, 50.0);
  std::vector<uint8_t> rgb(W * H * 3);
  renderer.renderView(scene, X_WC, K, rgb.data());
  double su = 0, sv = 0, n = 0;
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u)
      if (rgb[(v * W + u) * 3] > 50) su += u, sv += v, n += 1;
  ASSERT_GT(n, 30);
  // Analytic centre: X = -0.5, Y = -0.4 (optical), Z = 3 - 0.05 (the front face) ... use 3.
  const double u0 = K.fx * -0.5 / 3.0 + K.cx, v0 = K.fy * -0.4 / 3.0 + K.cy;
  EXPECT_NEAR(su / n, u0, 1.0);
  EXPECT_NEAR(sv / n, v0, 1.0);
}

TEST(RenderRenderer, AMeshThatFailsToLoadIsSkippedOthersStillRender) {
  std::vector<std::string> warnings;
  Renderer renderer([&](const std::string& w) { warnings.push_back(w); });
  Scene scene = boxScene(2.0, "Gazebo/Green");
  SceneItem bad;
  bad.body = 0;
  bad.shape.type = ShapeType::kMesh;
  bad.shape.mesh_path = std::string(TEST_DATA_DIR) + "/render/missing_mesh.stl";
  scene.items.insert(scene.items.begin(), bad);
  SceneItem empty = bad;
  empty.shape.mesh_path = std::string(TEST_DATA_DIR) + "/render/empty.stl";
  scene.items.push_back(empty);
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(32, 32, 1.0, 0.1, 10.0);
  std::vector<uint8_t> rgb(32 * 32 * 3);
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, rgb.data());
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, rgb.data());
  ASSERT_EQ(warnings.size(), 2u) << "one warning per broken mesh, not per frame";
  EXPECT_NE(warnings[0].find("missing_mesh.stl"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("empty.stl"), std::string::npos) << warnings[1];
  const uint8_t* px = &rgb[(16 * 32 + 16) * 3];
  EXPECT_LT(px[0], 10);
  EXPECT_GT(px[1], 100);  // the green box is there
}

TEST(RenderRenderer, MeshesRenderWithTheirFileGeometry) {
  Renderer renderer;
  Scene scene;
  scene.lights.push_back(DirectionalLight{});
  scene.sky = Eigen::Vector4f(0, 0, 0, 1);
  scene.addBody(SceneBody{"b", "m", true, Eigen::Isometry3d::Identity()});
  SceneItem item;
  item.shape.type = ShapeType::kMesh;
  item.shape.mesh_path = std::string(TEST_DATA_DIR) + "/urdf/meshes/cube.stl";
  item.shape.scale = Eigen::Vector3d(20, 20, 20);  // the 2 cm cube becomes 0.4 m
  item.material = findGazeboMaterial("Gazebo/White")->material;
  scene.items.push_back(item);
  const int W = 64, H = 64;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(W, H, 1.0, 0.1, 20.0);
  std::vector<float> depth(W * H);
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.translation().x() = -3.0;
  renderer.renderView(scene, X_WC, K, nullptr, depth.data());
  // The face towards the camera is at x = -0.2: depth 2.8 around the centre.
  EXPECT_NEAR(depth[(H / 2) * W + W / 2], 2.8, 1e-4);
  EXPECT_NEAR(depth[(H / 2 - 2) * W + W / 2 + 2], 2.8, 1e-4);
  EXPECT_TRUE(std::isinf(depth[0]));
}

TEST(RenderRenderer, PrimitivesHaveTheirSize) {
  // Depth at the centre pixel = distance to the nearest surface along the optical axis.
  Renderer renderer;
  const int W = 32, H = 32;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(W, H, 0.5, 0.05, 20.0);
  std::vector<float> depth(W * H);
  auto centreDepth = [&](const Shape& shape, const Eigen::Isometry3d& X_BS) {
    Scene scene;
    scene.lights.push_back(DirectionalLight{});
    scene.addBody(SceneBody{"b", "m", true, Eigen::Isometry3d::Identity()});
    SceneItem item;
    item.shape = shape;
    item.X_BS = X_BS;
    scene.items.push_back(item);
    renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, nullptr, depth.data());
    // The optical axis passes between the four centre pixels: average them.
    return 0.25 * (depth[15 * W + 15] + depth[15 * W + 16] + depth[16 * W + 15] + depth[16 * W + 16]);
  };
  const Eigen::Isometry3d at3(Eigen::Translation3d(3, 0, 0));
  Shape sphere;
  sphere.type = ShapeType::kSphere;
  sphere.radius = 0.5;
  EXPECT_NEAR(centreDepth(sphere, at3), 2.5, 0.01);  // tessellation: 32 x 16
  Shape cylinder;
  cylinder.type = ShapeType::kCylinder;
  cylinder.radius = 0.5;
  cylinder.length = 2.0;
  EXPECT_NEAR(centreDepth(cylinder, at3), 2.5, 0.01);
  // Lying along the optical axis: its cap at 3 - 1.
  EXPECT_NEAR(centreDepth(cylinder, at3 * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY())), 2.0, 1e-4);
  Shape box;
  box.type = ShapeType::kBox;
  box.size = Eigen::Vector3d(1.0, 0.2, 0.2);
  EXPECT_NEAR(centreDepth(box, at3), 2.5, 1e-4);
  // A bounded plane facing the camera (normal -x), and an unbounded one.
  Shape plane;
  plane.type = ShapeType::kPlane;
  plane.normal = Eigen::Vector3d(-1, 0, 0);
  plane.size = Eigen::Vector3d(1.0, 1.0, 0.0);
  EXPECT_NEAR(centreDepth(plane, at3), 3.0, 1e-4);
  plane.size = Eigen::Vector3d::Zero();
  EXPECT_NEAR(centreDepth(plane, at3), 3.0, 1e-4);
  plane.normal = Eigen::Vector3d(1, 0, 0);  // facing away: culled, like Gazebo
  EXPECT_TRUE(std::isinf(centreDepth(plane, at3)));
}

TEST(RenderRenderer, RenderingTwiceGivesIdenticalPixels) {
  Renderer renderer;
  Scene scene = boxScene(1.5, "Gazebo/Orange", 0.3);
  scene.ground_plane = true;
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.translation().z() = 0.3;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(80, 60, 1.2, 0.05, 8.0);
  std::vector<uint8_t> a(80 * 60 * 3), b(80 * 60 * 3);
  std::vector<float> da(80 * 60), db(80 * 60);
  renderer.renderView(scene, X_WC, K, a.data(), da.data());
  // Another size in between must not disturb the first target.
  std::vector<uint8_t> other(10 * 10 * 3);
  renderer.renderView(scene, X_WC, CameraIntrinsics::fromHorizontalFov(10, 10, 1.0, 0.1, 5.0), other.data());
  renderer.renderView(scene, X_WC, K, b.data(), db.data());
  EXPECT_EQ(a, b);
  EXPECT_EQ(0, std::memcmp(da.data(), db.data(), da.size() * sizeof(float)));
  EXPECT_EQ(renderer.frameCount(), 3u);
}

TEST(RenderRenderer, BodyPosesAreReadEveryFrame) {
  Renderer renderer;
  Scene scene = boxScene(1.0, "Gazebo/Grey");
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(16, 16, 1.0, 0.05, 8.0);
  std::vector<float> depth(16 * 16);
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, nullptr, depth.data());
  EXPECT_NEAR(depth[8 * 16 + 8], 1.0, 1e-4);
  scene.bodies[0].X_WB.translation().x() = 1.5;
  renderer.renderView(scene, Eigen::Isometry3d::Identity(), K, nullptr, depth.data());
  EXPECT_NEAR(depth[8 * 16 + 8], 2.5, 1e-4);
}

TEST(RenderRenderer, NoGlGivesAClearError) {
  ::setenv("TIANRACER_SIM_NO_GL", "1", 1);
  try {
    Renderer renderer;
    ADD_FAILURE() << "expected RenderError";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("TIANRACER_SIM_NO_GL"), std::string::npos) << e.what();
  }
  ::unsetenv("TIANRACER_SIM_NO_GL");
  Renderer renderer;  // and works again
  EXPECT_NE(renderer.glInfo().find("OpenGL"), std::string::npos);
}

TEST(RenderMaterials, StockValues) {
  const auto red = findGazeboMaterial("Gazebo/Red");
  ASSERT_TRUE(red);
  EXPECT_EQ(red->material.ambient.head<3>(), Eigen::Vector3f(1, 0, 0));
  EXPECT_EQ(red->material.diffuse.head<3>(), Eigen::Vector3f(1, 0, 0));
  EXPECT_FLOAT_EQ(red->material.specular[0], 0.1f);
  const auto grey = findGazeboMaterial("Gazebo/Grey");
  EXPECT_FLOAT_EQ(grey->material.ambient[0], 0.3f);
  EXPECT_FLOAT_EQ(grey->material.diffuse[0], 0.7f);
  EXPECT_FLOAT_EQ(grey->shininess, 1.5f);
  EXPECT_FLOAT_EQ(findGazeboMaterial("Gazebo/Orange")->material.diffuse[1], 0.5088f);
  EXPECT_FLOAT_EQ(findGazeboMaterial("Gazebo/DarkGrey")->material.diffuse[2], 0.175f);
  EXPECT_TRUE(findGazeboMaterial("Gazebo/Gray"));
  for (const char* n : {"Gazebo/Red", "Gazebo/Green", "Gazebo/Blue", "Gazebo/Grey", "Gazebo/DarkGrey",
                        "Gazebo/LightGrey", "Gazebo/Black", "Gazebo/White", "Gazebo/Orange",
                        "Gazebo/Yellow", "Gazebo/Wood"}) {
    EXPECT_TRUE(findGazeboMaterial(n)) << n;
  }
  EXPECT_FALSE(findGazeboMaterial("Gazebo/NoSuchThing"));
}

// The rest of gazebo.material's visible materials (Gazebo's own worlds use Gazebo/Grass,
// Gazebo/Runway, Gazebo/CoM, Gazebo/GreyTransparent): a glow is its parent's colour, a
// transparent one its (opaque) colour, a textured one its colours times the texture's mean.
TEST(RenderMaterials, EveryVisibleStockMaterialIsKnown) {
  for (const char* n :
       {"Gazebo/WhiteGlow", "Gazebo/RedGlow", "Gazebo/GreenGlow", "Gazebo/BlueGlow", "Gazebo/YellowGlow",
        "Gazebo/PurpleGlow", "Gazebo/TurquoiseGlow", "Gazebo/TurquoiseGlowOutline",
        "Gazebo/RedTransparent", "Gazebo/GreenTransparent", "Gazebo/BlueTransparent",
        "Gazebo/DarkMagentaTransparent", "Gazebo/GreyTransparent", "Gazebo/BlackTransparent",
        "Gazebo/YellowTransparent", "Gazebo/OrangeTransparent", "Gazebo/LightOn", "Gazebo/LightOff",
        "Gazebo/LightBlueLaser", "Gazebo/BlueLaser", "Gazebo/CoM", "Gazebo/JointAnchor",
        "Gazebo/CeilingTiled", "Gazebo/PaintedWall", "Gazebo/PioneerBody", "Gazebo/Pioneer2Body",
        "Gazebo/Road", "Gazebo/Residential", "Gazebo/Tertiary", "Gazebo/Pedestrian", "Gazebo/Footway",
        "Gazebo/Motorway", "Gazebo/Lanes_6", "Gazebo/Trunk", "Gazebo/Lanes_4", "Gazebo/Primary",
        "Gazebo/Lanes_2", "Gazebo/Secondary", "Gazebo/Lane_1", "Gazebo/Steps", "Gazebo/Runway",
        "Gazebo/Grass"}) {
    EXPECT_TRUE(findGazeboMaterial(n)) << n;
  }
  EXPECT_EQ(findGazeboMaterial("Gazebo/GreenGlow")->material.diffuse,
            findGazeboMaterial("Gazebo/Green")->material.diffuse);
  EXPECT_EQ(findGazeboMaterial("Gazebo/GreenGlow")->material.name, "Gazebo/GreenGlow");
  EXPECT_EQ(findGazeboMaterial("Gazebo/RedTransparent")->material.diffuse.head<3>(),
            Eigen::Vector3f(1, 0, 0));
  const auto grass = findGazeboMaterial("Gazebo/Grass");  // grass.jpg's mean, ambient 0.5
  EXPECT_GT(grass->material.diffuse[1], grass->material.diffuse[0]);  // green
  EXPECT_FLOAT_EQ(grass->material.ambient[1], 0.24f);
}

}  // namespace
}  // namespace tianracer_sim

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
