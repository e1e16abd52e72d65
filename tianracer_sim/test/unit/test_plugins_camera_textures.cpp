// Textures and materials in the renderer: UV orientation on a checkerboard quad, mesh files'
// own materials and textures (OBJ + MTL), a texture that cannot be read (diffuse colour and a
// warning), depth unaffected.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <stb/stb_image_write.h>

#include "tianracer_sim/plugins/camera/camera_sensor.h"
#include "tianracer_sim/render/image_file.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/scene/materials.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

namespace fs = std::filesystem;

// A fresh folder per test, <tmp>/tianracer_textures_XXXXXX, removed at its end.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("textures") {}
};

// 10 x 10 squares of `cell` px. Square (i, j), i from the left, j from the top of the image:
// red = 20 i + 20, green = 20 j + 20, blue = 255 on the checker's "black" squares ((i + j) even).
std::vector<uint8_t> checkerPixels(int cell) {
  const int n = 10 * cell;
  std::vector<uint8_t> rgb(static_cast<std::size_t>(n) * n * 3);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const int i = x / cell, j = y / cell;
      uint8_t* p = &rgb[(static_cast<std::size_t>(y) * n + x) * 3];
      p[0] = static_cast<uint8_t>(20 * i + 20);
      p[1] = static_cast<uint8_t>(20 * j + 20);
      p[2] = (i + j) % 2 == 0 ? 255 : 0;
    }
  }
  return rgb;
}

std::string writeChecker(const TempDir& dir, const std::string& name, bool jpeg = false) {
  const int cell = 16, n = 10 * cell;
  const auto rgb = checkerPixels(cell);
  const std::string path = dir.file(name);
  const int ok = jpeg ? stbi_write_jpg(path.c_str(), n, n, 3, rgb.data(), 100)
                      : stbi_write_png(path.c_str(), n, n, 3, rgb.data(), n * 3);
  EXPECT_NE(ok, 0) << path;
  return path;
}

// Only ambient light, scene ambient 1 and material ambient 1: a pixel is its texel.
Scene flatScene() {
  Scene scene;
  scene.ambient = Eigen::Vector4f(1, 1, 1, 1);
  scene.sky = Eigen::Vector4f(0, 0, 0, 1);
  scene.addBody(SceneBody{"quad::link", "quad", true, Eigen::Isometry3d::Identity()});
  return scene;
}

// flatScene() with the mesh file `path`, which has no material of its own: the file's.
Scene meshScene(const std::string& path) {
  Scene scene = flatScene();
  SceneItem item;
  item.shape.type = ShapeType::kMesh;
  item.shape.mesh_path = path;
  scene.items.push_back(item);
  return scene;
}

SceneItem quadItem(const std::string& texture, double size = 2.0) {
  SceneItem item;
  item.shape.type = ShapeType::kPlane;
  item.shape.normal = Eigen::Vector3d::UnitZ();
  item.shape.size = Eigen::Vector3d(size, size, 0);
  item.material.ambient = Eigen::Vector4f(1, 1, 1, 1);
  item.material.diffuse = Eigen::Vector4f(1, 1, 1, 1);
  item.material.specular = Eigen::Vector4f(0, 0, 0, 1);
  item.material.texture = texture;
  item.material.specified = true;
  return item;
}

// A camera `h` above the origin looking straight down, image right = world +x, image up =
// world +y (camera link: x forward = -z, y left = -x, z up = +y).
Eigen::Isometry3d lookingDown(double h) {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d R;
  R.col(0) = Eigen::Vector3d(0, 0, -1);
  R.col(1) = Eigen::Vector3d(-1, 0, 0);
  R.col(2) = Eigen::Vector3d(0, 1, 0);
  X_WC.linear() = R;
  X_WC.translation() = Eigen::Vector3d(0, 0, h);
  return X_WC;
}

// Pixel of world point (x, y, 0) seen by lookingDown(h) with intrinsics K.
Eigen::Vector2d pixelOf(const CameraIntrinsics& K, double h, double x, double y) {
  return {K.fx * x / h + K.cx, K.fy * (-y) / h + K.cy};
}

TEST(RenderTextures, CheckerboardQuadHasTheRightSquaresInTheRightPlaces) {
  TempDir dir;
  for (bool jpeg : {false, true}) {
    const std::string tex = writeChecker(dir, jpeg ? "checker.jpg" : "checker.png", jpeg);
    std::vector<std::string> warnings;
    Renderer renderer([&](const std::string& w) { warnings.push_back(w); });
    Scene scene = flatScene();
    SceneItem item = quadItem(tex);
    item.X_BS.translation() = Eigen::Vector3d(0, 0, 0);
    scene.items.push_back(item);
    const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(240, 240, 1.2, 0.05, 10.0);
    const double h = 1.2 / std::tan(0.6);  // the image spans 2.4 m: the 2 m quad and a margin
    std::vector<uint8_t> rgb(240 * 240 * 3);
    renderer.renderView(scene, lookingDown(h), K, rgb.data());
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    int checked = 0;
    for (int j = 0; j < 10; ++j) {
      for (int i = 0; i < 10; ++i) {
        // Centre of square (i, j): the image's left edge at x = -1, its top edge at y = +1.
        const Eigen::Vector2d px = pixelOf(K, h, -1.0 + 0.2 * i + 0.1, 1.0 - 0.2 * j - 0.1);
        const int u = static_cast<int>(std::lround(px.x())), v = static_cast<int>(std::lround(px.y()));
        const uint8_t* p = &rgb[(v * 240 + u) * 3];
        const int tol = jpeg ? 14 : 6;
        EXPECT_NEAR(p[0], 20 * i + 20, tol) << "square " << i << "," << j << (jpeg ? " jpeg" : " png");
        EXPECT_NEAR(p[1], 20 * j + 20, tol) << "square " << i << "," << j;
        EXPECT_NEAR(p[2], (i + j) % 2 == 0 ? 255 : 0, tol + 10) << "square " << i << "," << j;
        ++checked;
      }
    }
    EXPECT_EQ(checked, 100);
    // Outside the quad: the sky.
    EXPECT_EQ(rgb[0], 0);
  }
}

TEST(RenderTextures, TextureScaleRepeatsAboutTheCentre) {
  // OGRE's `scale 0.5 0.5` shrinks the texture to half: the quad shows it 2 x 2 times.
  TempDir dir;
  const std::string tex = writeChecker(dir, "checker.png");
  Renderer renderer;
  Scene scene = flatScene();
  SceneItem item = quadItem(tex);
  item.material.texture_scale = Eigen::Vector2f(0.5f, 0.5f);
  scene.items.push_back(item);
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(240, 240, 1.2, 0.05, 10.0);
  const double h = 1.2 / std::tan(0.6);
  std::vector<uint8_t> rgb(240 * 240 * 3);
  renderer.renderView(scene, lookingDown(h), K, rgb.data());
  // The quad's u = x / 2 + 1/2 becomes u' = (u - 1/2) / 0.5 + 1/2 = x + 1/2 (repeating): square 0
  // (red 20) at x = -0.45 and 0.55, square 5 (red 120) at x = -0.95 and 0.05. Scaling about
  // the origin instead (u' = 2u) would swap them.
  for (const auto& xr : {std::make_pair(-0.45, 20), std::make_pair(0.55, 20), std::make_pair(-0.95, 120),
                         std::make_pair(0.05, 120)}) {
    const Eigen::Vector2d px = pixelOf(K, h, xr.first, 0.0);
    const uint8_t* p = &rgb[(static_cast<int>(std::lround(px.y())) * 240 + static_cast<int>(std::lround(px.x()))) * 3];
    EXPECT_NEAR(p[0], xr.second, 8) << "x " << xr.first;
  }
}

TEST(RenderTextures, UnreadableTextureDrawsTheDiffuseColourAndWarnsOnce) {
  TempDir dir;
  const std::string garbage = dir.file("garbage.png");
  std::ofstream(garbage) << "this is not a PNG file";
  const std::string missing = dir.file("missing.png");
  for (const std::string& bad : {garbage, missing}) {
    std::vector<std::string> warnings;
    Renderer renderer([&](const std::string& w) { warnings.push_back(w); });
    Scene scene = flatScene();
    SceneItem item = quadItem(bad);
    item.material.ambient = Eigen::Vector4f(0.2f, 0.6f, 0.4f, 1.0f);
    scene.items.push_back(item);
    const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(32, 32, 0.5, 0.05, 10.0);
    std::vector<uint8_t> rgb(32 * 32 * 3);
    renderer.renderView(scene, lookingDown(1.0), K, rgb.data());
    renderer.renderView(scene, lookingDown(1.0), K, rgb.data());
    const uint8_t* p = &rgb[(16 * 32 + 16) * 3];
    EXPECT_NEAR(p[0], 51, 1);
    EXPECT_NEAR(p[1], 153, 1);
    EXPECT_NEAR(p[2], 102, 1);
    ASSERT_EQ(warnings.size(), 1u);  // once, not every frame
    EXPECT_NE(warnings[0].find(bad), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find(bad == garbage ? "cannot be decoded" : "not found"), std::string::npos)
        << warnings[0];
    EXPECT_NE(warnings[0].find("diffuse colour"), std::string::npos) << warnings[0];
  }
  EXPECT_THROW(readImageFile(garbage), ImageFileError);
}

TEST(RenderTextures, DepthIsTheSameWithAndWithoutTexture) {
  TempDir dir;
  const std::string tex = writeChecker(dir, "checker.png");
  Renderer renderer;
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(64, 48, 1.0, 0.05, 10.0);
  Eigen::Isometry3d X_WC = lookingDown(1.5);
  X_WC.linear() = X_WC.linear() * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  std::vector<float> depth_tex(64 * 48), depth_plain(64 * 48);
  std::vector<uint8_t> rgb_tex(64 * 48 * 3), rgb_plain(64 * 48 * 3);
  Scene textured = flatScene();
  textured.items.push_back(quadItem(tex));
  Scene plain = flatScene();
  plain.items.push_back(quadItem(""));
  renderer.renderView(textured, X_WC, K, rgb_tex.data(), depth_tex.data());
  renderer.renderView(plain, X_WC, K, rgb_plain.data(), depth_plain.data());
  EXPECT_EQ(depth_tex, depth_plain);
  EXPECT_NE(rgb_tex, rgb_plain);
}

// An OBJ quad with an MTL: material "board" with a diffuse texture map, material "paint" with
// a diffuse colour only. Each half of the quad has one of them.
TEST(RenderTextures, MeshFilesKeepTheirMaterialsAndTextures) {
  TempDir dir;
  writeChecker(dir, "board.png");
  std::ofstream(dir.file("quad.mtl")) << "newmtl board\nKd 1 1 1\nKa 1 1 1\nmap_Kd board.png\n\n"
                                         "newmtl paint\nKd 0.2 0.4 0.9\nKa 0.2 0.4 0.9\n";
  // Left half (x in [-1, 0]) textured with u = x + 1, v = y / 2 + 0.5 (the texture's left half);
  // right half painted.
  std::ofstream(dir.file("quad.obj")) << "mtllib quad.mtl\n"
                                         "v -1 -1 0\nv 0 -1 0\nv 0 1 0\nv -1 1 0\nv 1 -1 0\nv 1 1 0\n"
                                         "vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\n"
                                         "usemtl board\nf 1/1 2/2 3/3 4/4\n"
                                         "usemtl paint\nf 2/2 5/2 6/3 3/3\n";
  std::vector<std::string> warnings;
  Renderer renderer([&](const std::string& w) { warnings.push_back(w); });
  Scene scene = meshScene(dir.file("quad.obj"));
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(240, 240, 1.2, 0.05, 10.0);
  const double h = 1.2 / std::tan(0.6);
  std::vector<uint8_t> rgb(240 * 240 * 3);
  renderer.renderView(scene, lookingDown(h), K, rgb.data());
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  auto at = [&](double x, double y) {
    const Eigen::Vector2d px = pixelOf(K, h, x, y);
    return &rgb[(static_cast<int>(std::lround(px.y())) * 240 + static_cast<int>(std::lround(px.x()))) * 3];
  };
  // The textured half shows squares i = 0..4 left to right, j = 0..9 top to bottom.
  for (int i = 0; i < 5; ++i) {
    for (int j : {0, 4, 9}) {
      const uint8_t* p = at(-1.0 + 0.2 * i + 0.1, 1.0 - 0.2 * j - 0.1);
      EXPECT_NEAR(p[0], 20 * i + 20, 8) << i << "," << j;
      EXPECT_NEAR(p[1], 20 * j + 20, 8) << i << "," << j;
    }
  }
  const uint8_t* paint = at(0.5, 0.0);
  EXPECT_NEAR(paint[0], 51, 2);
  EXPECT_NEAR(paint[1], 102, 2);
  EXPECT_NEAR(paint[2], 230, 2);
  // A material the user wrote replaces the file's colours; the file's texture stays.
  scene.items[0].material = findGazeboMaterial("Gazebo/Red")->material;
  scene.items[0].material.specular = Eigen::Vector4f(0, 0, 0, 1);
  renderer.renderView(scene, lookingDown(h), K, rgb.data());
  EXPECT_NEAR(at(0.5, 0.0)[0], 255, 2);
  EXPECT_NEAR(at(0.5, 0.0)[2], 0, 2);
  EXPECT_NEAR(at(-0.9, 0.9)[0], 20, 8);  // texel red 20 times ambient red 1
  EXPECT_NEAR(at(-0.9, 0.9)[1], 0, 2);   // texel green times ambient green 0
}

TEST(RenderTextures, MeshTextureThatIsMissingWarnsNamingMeshAndFile) {
  TempDir dir;
  std::ofstream(dir.file("quad.mtl")) << "newmtl board\nKd 0.5 0.5 0.5\nmap_Kd nowhere.png\n";
  std::ofstream(dir.file("quad.obj")) << "mtllib quad.mtl\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                                         "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl board\nf 1/1 2/2 3/3 4/4\n";
  std::vector<std::string> warnings;
  Renderer renderer([&](const std::string& w) { warnings.push_back(w); });
  Scene scene = meshScene(dir.file("quad.obj"));
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(32, 32, 0.5, 0.05, 10.0);
  std::vector<uint8_t> rgb(32 * 32 * 3);
  renderer.renderView(scene, lookingDown(2.0), K, rgb.data());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("quad.obj"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("'nowhere.png' not found"), std::string::npos) << warnings[0];
  EXPECT_NEAR(rgb[(16 * 32 + 16) * 3], 128, 2);  // the diffuse grey
}

}  // namespace
}  // namespace tianracer_sim
