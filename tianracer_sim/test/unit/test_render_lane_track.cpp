// The shipped lane track (worlds/lane_track.world): its floor material resolves to the
// shipped texture through the model's OGRE script, and the camera image from the start shows
// the lane lines.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/scene/ogre_material.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

// The shipped worlds/lane_track.world, which loads without a warning.
WorldDescription loadLaneTrack() {
  std::vector<std::string> warnings;
  WorldLoadOptions options;
  options.warn = [&](const std::string& w) { warnings.push_back(w); };
  const WorldDescription w = loadWorldFile(TEST_DATA_DIR "/../../worlds/lane_track.world", options);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  return w;
}

TEST(RenderLaneTrack, FloorMaterialResolvesToTheShippedTexture) {
  const WorldDescription w = loadLaneTrack();
  const ModelDescription* track = nullptr;
  for (const auto& m : w.models) {
    if (m.name == "lane_track") track = &m;
  }
  ASSERT_NE(track, nullptr);
  const Material& m = track->links.at(0).visuals.at(0).material;
  EXPECT_EQ(std::filesystem::path(m.texture).filename(), "lane_track.png");
  EXPECT_TRUE(std::filesystem::exists(m.texture));
  EXPECT_LT(std::filesystem::file_size(m.texture), 500u * 1024u);  // small enough to ship
}

TEST(RenderLaneTrack, OgreScriptIsFoundInTheModelsFolder) {
  const auto m = findOgreMaterial("LaneTrack/Floor", {TEST_DATA_DIR "/../../worlds/models/lane_track/materials/scripts"});
  ASSERT_TRUE(m);
  EXPECT_EQ(m->texture, "lane_track.png");
}

// The shipped lane track as the tianracer's camera sees it from the start: the white edge
// lines stand out of the asphalt along an image row, where the K projection puts them.
TEST(RenderLaneTrack, CameraImageShowsTheLaneLines) {
  const WorldDescription world = loadLaneTrack();
  std::vector<std::string> warnings;
  Scene scene;
  addToScene(world, scene);
  Renderer renderer([&](const std::string& w) { warnings.push_back(w); });
  // A 640 x 480 camera 0.3 m above the start line, looking along +x, pitched down 0.35 rad.
  const CameraIntrinsics K = CameraIntrinsics::fromHorizontalFov(640, 480, 1.3962634, 0.02, 50.0);
  const double pitch = 0.35, z = 0.3;
  Eigen::Isometry3d X_WC = Eigen::Translation3d(0, 0, z) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY());
  std::vector<uint8_t> rgb(640 * 480 * 3);
  renderer.renderView(scene, X_WC, K, rgb.data());
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  // Row 250: the ground it sees lies about 0.75 m ahead, the lines at y = +-0.525.
  const int row = 250;
  const double angle = pitch + std::atan((row - K.cy) / K.fy);
  const double d = (z - 0.002) / std::tan(angle);  // the floor is 2 mm up
  auto lum = [&](int u) {
    const uint8_t* p = &rgb[(row * 640 + u) * 3];
    return 0.299 * p[0] + 0.587 * p[1] + 0.114 * p[2];
  };
  for (double y : {0.525, -0.525}) {
    // Optical x = -y_world; the optical depth of the point is d cos(pitch) + ... : project it.
    const Eigen::Vector3d p_W(d, y, 0.002);
    const Eigen::Vector3d p_C = X_WC.inverse() * p_W;  // link frame: x forward, y left, z up
    const double u = K.fx * (-p_C.y()) / p_C.x() + K.cx;
    const int ui = static_cast<int>(std::lround(u));
    ASSERT_GT(ui, 20);
    ASSERT_LT(ui, 620);
    // The line: bright; 30 px towards the road's middle: asphalt, dark.
    const int inward = y > 0 ? +1 : -1;  // +y is image left: the middle is to the right of it
    double line = 0;
    for (int k = -2; k <= 2; ++k) line = std::max(line, lum(ui + k));
    const double asphalt = lum(ui + inward * 30);
    EXPECT_GT(line, 170) << "line y " << y << " at u " << u;
    EXPECT_LT(asphalt, 90) << "asphalt next to line y " << y;
    EXPECT_GT(line - asphalt, 100) << "contrast at y " << y;
  }
}

}  // namespace
}  // namespace tianracer_sim
