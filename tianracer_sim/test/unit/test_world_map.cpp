// A world from a ROS map (map_server YAML + map_saver PGM): occupied cells become few boxes.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

#include "tianracer_sim/world/map_world.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

const std::string kMaps = std::string(TEST_DATA_DIR) + "/maps/";

// room.pgm (40 x 30 cells of 5 cm): a border wall 2 cells thick (264 cells), a 3 x 10 pillar
// (30), one single cell (1) and a patch of unknown (205, not occupied).
constexpr int kOccupied = 264 + 30 + 1;

int count(const OccupancyImage& img) {
  int n = 0;
  for (bool o : img.occupied) n += o;
  return n;
}

TEST(MapWorld, NegateZeroAndOneGiveTheSameWalls) {
  const MapDescription a = loadMapYaml(kMaps + "room.yaml", 0.5);
  const MapDescription b = loadMapYaml(kMaps + "room_negated.yaml", 0.5);
  EXPECT_FALSE(a.negate);
  EXPECT_TRUE(b.negate);
  const OccupancyImage ia = loadOccupancy(a, kMaps + "room.yaml");
  const OccupancyImage ib = loadOccupancy(b, kMaps + "room_negated.yaml");
  ASSERT_EQ(ia.width, 40);
  ASSERT_EQ(ia.height, 30);
  EXPECT_EQ(count(ia), kOccupied);
  EXPECT_EQ(ia.occupied, ib.occupied);
  EXPECT_TRUE(ia.at(0, 0) && ia.at(16, 15) && ia.at(30, 24));
  EXPECT_FALSE(ia.at(26, 6));  // unknown is not a wall
  EXPECT_FALSE(ia.at(5, 5));

  const WorldDescription wa = loadWorldFile(kMaps + "room.yaml");
  const WorldDescription wb = loadWorldFile(kMaps + "room_negated.yaml");
  ASSERT_EQ(wa.models.size(), 1u);
  const auto& ca = wa.models[0].links[0].collisions;
  const auto& cb = wb.models[0].links[0].collisions;
  ASSERT_EQ(ca.size(), cb.size());
  // Few boxes, not one per cell: 4 border walls, the pillar, the single cell.
  EXPECT_EQ(ca.size(), 6u);
  double area = 0.0;
  Eigen::AlignedBox3d bounds_a, bounds_b;
  for (std::size_t i = 0; i < ca.size(); ++i) {
    EXPECT_TRUE(ca[i].X_LS.translation().head<2>().isApprox(cb[i].X_LS.translation().head<2>()));
    EXPECT_TRUE(ca[i].shape.size.head<2>().isApprox(cb[i].shape.size.head<2>()));
    area += ca[i].shape.size.x() * ca[i].shape.size.y();
    for (const auto* c : {&ca[i], &cb[i]}) {
      const auto& world = c == &ca[i] ? wa : wb;
      const Eigen::Vector3d centre = (world.models[0].X_WM * c->X_LS).translation();
      (c == &ca[i] ? bounds_a : bounds_b).extend(centre + 0.5 * c->shape.size);
      (c == &ca[i] ? bounds_a : bounds_b).extend(centre - 0.5 * c->shape.size);
    }
  }
  EXPECT_NEAR(area, kOccupied * 0.05 * 0.05, 1e-9);  // exactly the occupied cells
  // The image's lower-left corner at origin (-1, -0.5): walls span 2 m x 1.5 m from there.
  EXPECT_TRUE(bounds_a.min().head<2>().isApprox(Eigen::Vector2d(-1.0, -0.5)));
  EXPECT_TRUE(bounds_a.max().head<2>().isApprox(Eigen::Vector2d(1.0, 1.0)));
  EXPECT_TRUE(bounds_b.min().head<2>().isApprox(bounds_a.min().head<2>()));
  EXPECT_TRUE(bounds_b.max().head<2>().isApprox(bounds_a.max().head<2>()));
  // Wall height: the default 0.5 m, or the YAML's wall_height.
  EXPECT_NEAR(bounds_a.max().z(), 0.5, 1e-12);
  EXPECT_NEAR(bounds_a.min().z(), 0.0, 1e-12);
  EXPECT_NEAR(bounds_b.max().z(), 0.3, 1e-12);
  EXPECT_TRUE(wa.ground_plane);
  EXPECT_TRUE(wa.models[0].is_static);
}

TEST(MapWorld, MergedRectanglesCoverExactlyTheOccupiedCells) {
  OccupancyImage img;
  img.width = 7;
  img.height = 5;
  const char* rows[] = {"##..###", "##..#..", "....#..", "#######", "..#...#"};
  for (const char* r : rows)
    for (int c = 0; c < img.width; ++c) img.occupied.push_back(r[c] == '#');
  const auto rects = mergeOccupiedCells(img);
  std::vector<int> cover(img.occupied.size(), 0);
  for (const CellRect& r : rects) {
    for (int y = r.row; y < r.row + r.rows; ++y)
      for (int x = r.col; x < r.col + r.cols; ++x) ++cover[y * img.width + x];
  }
  for (std::size_t i = 0; i < cover.size(); ++i) EXPECT_EQ(cover[i], img.occupied[i] ? 1 : 0) << i;
  EXPECT_LE(rects.size(), 7u);
}

std::string errorOf(const std::string& yaml) {
  return test::errorText<WorldError>([&] { loadWorldFile(kMaps + yaml); }, "(no error)");
}

TEST(MapWorld, BadInputNamesFileAndValue) {
  std::string e = errorOf("missing_image.yaml");
  EXPECT_NE(e.find("missing_image.yaml: map image '"), std::string::npos) << e;
  EXPECT_NE(e.find("nowhere.pgm' does not exist"), std::string::npos) << e;
  e = errorOf("zero_resolution.yaml");
  EXPECT_NE(e.find("zero_resolution.yaml:2: 'resolution' must be > 0 m/cell (got 0.0)"), std::string::npos) << e;
  e = errorOf("negative_resolution.yaml");
  EXPECT_NE(e.find("negative_resolution.yaml:3: 'resolution' must be > 0 m/cell (got -0.05)"),
            std::string::npos) << e;
  // An image that is not one: named with stb_image's reason.
  e = "";
  try {
    MapDescription m;
    m.image = kMaps + "room.yaml";
    m.resolution = 0.05;
    loadOccupancy(m, "x.yaml");
  } catch (const WorldError& err) {
    e = err.what();
  }
  EXPECT_NE(e.find("cannot be decoded"), std::string::npos) << e;
}

// The shipped map of the racetrack (scripts/world_to_map.py): few boxes, and the car's start
// line and the bottom straight are clear, as in racetrack.world.
TEST(MapWorld, ShippedRacetrackMap) {
  const std::string yaml = std::string(TEST_DATA_DIR) + "/../../worlds/racetrack_map.yaml";
  const MapDescription map = loadMapYaml(yaml, 0.5);
  const OccupancyImage img = loadOccupancy(map, yaml);
  const WorldDescription w = loadWorldFile(yaml);
  const auto& boxes = w.models[0].links[0].collisions;
  std::cout << "[racetrack map] " << img.width << " x " << img.height << " cells, " << count(img)
            << " occupied, " << boxes.size() << " boxes\n";
  EXPECT_LT(boxes.size() * 4, static_cast<std::size_t>(count(img)));
  for (const auto& c : boxes) {
    const Eigen::Vector3d p = (w.models[0].X_WM * c.X_LS).translation();
    EXPECT_NEAR(c.shape.size.z(), 0.3, 1e-12);
    // Nothing within 0.45 m of the bottom straight's centreline (y = 0, |x| <= 2.75).
    if (std::abs(p.x()) <= 2.75) EXPECT_GT(std::abs(p.y()) - 0.5 * c.shape.size.y(), 0.45) << p.transpose();
  }
}

}  // namespace
}  // namespace tianracer_sim
