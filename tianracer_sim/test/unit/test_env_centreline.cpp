// The centreline: arc lengths, projections (with and without a hint), progress round a lap.
#include <gtest/gtest.h>

#include <cmath>

#include "tianracer_sim/env/centreline.h"

namespace tianracer_sim {
namespace {

Centreline square(bool closed) {
  return Centreline({{0, 0}, {2, 0}, {2, 2}, {0, 2}}, closed);
}

TEST(Centreline, LengthClosedAndOpen) {
  EXPECT_DOUBLE_EQ(square(true).length(), 8.0);
  EXPECT_DOUBLE_EQ(square(false).length(), 6.0);
  // A repeated first point at the end is the same lap.
  EXPECT_DOUBLE_EQ(Centreline({{0, 0}, {2, 0}, {2, 2}, {0, 2}, {0, 0}}, true).length(), 8.0);
}

TEST(Centreline, ProjectionGivesArcLengthAndSignedOffset) {
  const Centreline c = square(true);
  Centreline::Projection p = c.project({1.0, 0.25});
  EXPECT_DOUBLE_EQ(p.s, 1.0);
  EXPECT_DOUBLE_EQ(p.lateral, 0.25);  // left of travel (+x) is +y
  p = c.project({1.0, -0.5});
  EXPECT_DOUBLE_EQ(p.lateral, -0.5);
  p = c.project({-0.1, 1.0});  // on the closing segment (0,2) -> (0,0)
  EXPECT_DOUBLE_EQ(p.s, 7.0);
  EXPECT_EQ(p.segment, 3);
  // A hint searches near it only: the same answer when the point is near.
  EXPECT_DOUBLE_EQ(c.project({1.9, 0.1}, 0, 1).s, c.project({1.9, 0.1}).s);
}

TEST(Centreline, ProgressWrapsRoundTheLap) {
  const Centreline c = square(true);
  EXPECT_DOUBLE_EQ(c.advance(7.5, 0.5), 1.0);   // over the start line, forward
  EXPECT_DOUBLE_EQ(c.advance(0.5, 7.5), -1.0);  // backward
  EXPECT_DOUBLE_EQ(square(false).advance(5.0, 1.0), -4.0);
}

TEST(Centreline, PoseAlongTheLine) {
  const Centreline c = square(true);
  Eigen::Vector3d p = c.pose(3.0);
  EXPECT_DOUBLE_EQ(p.x(), 2.0);
  EXPECT_DOUBLE_EQ(p.y(), 1.0);
  EXPECT_DOUBLE_EQ(p.z(), M_PI / 2);
  p = c.pose(9.0);  // wraps
  EXPECT_DOUBLE_EQ(p.x(), 1.0);
  EXPECT_DOUBLE_EQ(p.y(), 0.0);
  EXPECT_DOUBLE_EQ(square(false).pose(100.0).y(), 2.0);  // clamped at the end
}

TEST(Centreline, BadInput) {
  EXPECT_THROW(Centreline({{0, 0}}, false), std::invalid_argument);
  EXPECT_THROW(Centreline({{0, 0}, {0, 0}}, false), std::invalid_argument);
  EXPECT_THROW(Centreline({{0, 0}, {NAN, 1}}, false), std::invalid_argument);
}

}  // namespace
}  // namespace tianracer_sim
