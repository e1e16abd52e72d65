// joint_trajectory_controller's spline segment and segment lookup, with the cases and numbers of
// ros_controllers' quintic_spline_segment_test.cpp and trajectory_interface_test.cpp.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_control/trajectory/spline_segment.h"

using tianracer_control::trajectory::findSegment;
using tianracer_control::trajectory::sampleSegments;
using tianracer_control::trajectory::SplineSegment;
using tianracer_control::trajectory::State;

namespace {

constexpr double kEps = 1e-9;

State posOnly(double p) {
  State s;
  s.position = {p};
  return s;
}

State posVel(double p, double v) {
  State s = posOnly(p);
  s.velocity = {v};
  return s;
}

State posVelAcc(double p, double v, double a) {
  State s = posVel(p, v);
  s.acceleration = {a};
  return s;
}

void expectState(const SplineSegment& segment, double t, double p, double v, double a) {
  State s;
  segment.sample(t, s);
  ASSERT_EQ(s.position.size(), 1u);
  EXPECT_NEAR(s.position[0], p, kEps) << "t=" << t;
  EXPECT_NEAR(s.velocity[0], v, kEps) << "t=" << t;
  EXPECT_NEAR(s.acceleration[0], a, kEps) << "t=" << t;
}

std::string initError(double t0, const State& s0, double t1, const State& s1) {
  try {
    SplineSegment(t0, s0, t1, s1);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(TrajectorySegment, TimesAndTimeFromStart) {
  State start = posOnly(0.0);
  start.time_from_start = 0.25;
  const SplineSegment segment(1.0, start, 2.0, posOnly(2.0));
  EXPECT_EQ(segment.startTime(), 1.0);
  EXPECT_EQ(segment.endTime(), 2.0);
  EXPECT_EQ(segment.timeFromStart(), 0.25);
  EXPECT_EQ(segment.size(), 1u);
}

TEST(TrajectorySegment, InvalidConstructionSaysWhy) {
  const State ok = posVelAcc(0.0, 0.0, 0.0);
  EXPECT_EQ(initError(1.0, State(), 2.0, ok),
            "Quintic spline segment can't be constructed: Endpoint positions can't be empty.");
  EXPECT_EQ(initError(1.0, ok, 2.0, State()),
            "Quintic spline segment can't be constructed: Endpoint positions can't be empty.");
  EXPECT_EQ(initError(1.0, State(2), 2.0, ok),
            "Quintic spline segment can't be constructed: Endpoint positions size mismatch.");
  State bad_vel = ok;
  bad_vel.velocity.push_back(0.0);
  EXPECT_EQ(initError(1.0, bad_vel, 2.0, ok),
            "Quintic spline segment can't be constructed: Start state velocity size mismatch.");
  EXPECT_EQ(initError(1.0, ok, 2.0, bad_vel),
            "Quintic spline segment can't be constructed: End state velocity size mismatch.");
  State bad_acc = ok;
  bad_acc.acceleration.push_back(0.0);
  EXPECT_EQ(initError(1.0, bad_acc, 2.0, ok),
            "Quintic spline segment can't be constructed: Start state acceleration size mismatch.");
  EXPECT_EQ(initError(1.0, ok, 2.0, bad_acc),
            "Quintic spline segment can't be constructed: End state acceleration size mismatch.");
  EXPECT_EQ(initError(1.0, ok, -1.0, ok),
            "Quintic spline segment can't be constructed: end_time < start_time.");
}

TEST(TrajectorySegment, EmptySegmentSamplesEmpty) {
  const SplineSegment segment;
  State s(1);
  segment.sample(1.0, s);
  EXPECT_TRUE(s.position.empty());
  EXPECT_TRUE(s.velocity.empty());
  EXPECT_TRUE(s.acceleration.empty());
  EXPECT_EQ(segment.size(), 0u);
}

// Zero duration: the start state's terms; outside the instant, held with zero rates.
TEST(TrajectorySegment, ZeroDuration) {
  const SplineSegment pos(1.0, posOnly(1.0), 1.0, posOnly(2.0));
  expectState(pos, -1.0, 1.0, 0.0, 0.0);
  expectState(pos, 1.0, 1.0, 0.0, 0.0);
  expectState(pos, 2.0, 1.0, 0.0, 0.0);

  const SplineSegment vel(1.0, posVel(1.0, 2.0), 1.0, posVel(2.0, 4.0));
  expectState(vel, -1.0, 1.0, 0.0, 0.0);
  expectState(vel, 1.0, 1.0, 2.0, 0.0);
  expectState(vel, 2.0, 1.0, 0.0, 0.0);

  const SplineSegment acc(1.0, posVelAcc(1.0, 2.0, 3.0), 1.0, posVelAcc(2.0, 4.0, 6.0));
  expectState(acc, -1.0, 1.0, 0.0, 0.0);
  expectState(acc, 1.0, 1.0, 2.0, 3.0);
  expectState(acc, 2.0, 1.0, 0.0, 0.0);
}

// Positions only (the end's velocity and acceleration are ignored): linear.
TEST(TrajectorySegment, LinearFromPositions) {
  const SplineSegment segment(1.0, posOnly(0.0), 3.0, posVelAcc(2.0, 0.0, 0.0));
  expectState(segment, -1.0, 0.0, 0.0, 0.0);
  expectState(segment, 1.0, 0.0, 1.0, 0.0);
  expectState(segment, 2.0, 1.0, 1.0, 0.0);
  expectState(segment, 3.0, 2.0, 1.0, 0.0);
  expectState(segment, 5.0, 2.0, 0.0, 0.0);
}

// Positions and velocities: cubic; start and end from x^3 - 2x on [0, 2].
TEST(TrajectorySegment, CubicFromPositionsAndVelocities) {
  const SplineSegment segment(1.0, posVel(0.0, -2.0), 3.0, posVelAcc(4.0, 10.0, 0.0));
  expectState(segment, -1.0, 0.0, 0.0, 0.0);
  expectState(segment, 1.0, 0.0, -2.0, 0.0);
  expectState(segment, 1.0 + std::sqrt(2.0), 0.0, 4.0, 6.0 * std::sqrt(2.0));
  expectState(segment, 3.0, 4.0, 10.0, 12.0);
  expectState(segment, 5.0, 4.0, 0.0, 0.0);
}

// All three: quintic; from x(x-1)(x-2)(x-3)(x-4) = x^5 - 10x^4 + 35x^3 - 50x^2 + 24x on [0, 2].
TEST(TrajectorySegment, QuinticFromPositionsVelocitiesAccelerations) {
  const SplineSegment segment(1.0, posVelAcc(0.0, 24.0, -100.0), 3.0, posVelAcc(0.0, 4.0, 0.0));
  expectState(segment, -1.0, 0.0, 0.0, 0.0);
  expectState(segment, 1.0, 0.0, 24.0, -100.0);
  // Zero crossing at x = 1: p' = 5 - 40 + 105 - 100 + 24 = -6, p'' = 20 - 120 + 210 - 100 = 10
  expectState(segment, 2.0, 0.0, -6.0, 10.0);
  expectState(segment, 3.0, 0.0, 4.0, 0.0);
  expectState(segment, 5.0, 0.0, 0.0, 0.0);
}

// The lowest level both states give: velocities on one side only -> linear.
TEST(TrajectorySegment, LowestCommonLevel) {
  const SplineSegment segment(0.0, posVelAcc(0.0, 5.0, 7.0), 2.0, posOnly(4.0));
  expectState(segment, 1.0, 2.0, 2.0, 0.0);
}

TEST(TrajectorySegment, MultiDimensional) {
  State s0(2), s1(2);
  s0.acceleration.clear();
  s1.acceleration.clear();
  s0.position = {0.0, 1.0};
  s0.velocity = {-2.0, 0.0};
  s1.position = {4.0, 1.0};
  s1.velocity = {10.0, 0.0};
  const SplineSegment segment(1.0, s0, 3.0, s1);
  State s;
  segment.sample(1.0 + std::sqrt(2.0), s);
  ASSERT_EQ(s.position.size(), 2u);
  EXPECT_NEAR(s.position[0], 0.0, kEps);
  EXPECT_NEAR(s.velocity[0], 4.0, kEps);
  EXPECT_NEAR(s.position[1], 1.0, kEps);
  EXPECT_NEAR(s.velocity[1], 0.0, kEps);
}

// findSegment: the last segment starting at or before t; end() before the first (and for none).
TEST(TrajectorySegment, FindAndSampleSegments) {
  std::vector<SplineSegment> segments;
  EXPECT_EQ(findSegment(segments, 1.0), segments.end());
  segments.emplace_back(1.0, posOnly(0.0), 2.0, posOnly(1.0));
  segments.emplace_back(2.0, posOnly(1.0), 4.0, posOnly(3.0));
  segments.emplace_back(5.0, posOnly(3.0), 6.0, posOnly(4.0));  // gap 4..5
  EXPECT_EQ(findSegment(segments, 0.5), segments.end());
  EXPECT_EQ(findSegment(segments, 1.0), segments.begin());
  EXPECT_EQ(findSegment(segments, 1.9), segments.begin());
  EXPECT_EQ(findSegment(segments, 2.0), segments.begin() + 1);
  EXPECT_EQ(findSegment(segments, 4.5), segments.begin() + 1);
  EXPECT_EQ(findSegment(segments, 5.0), segments.begin() + 2);
  EXPECT_EQ(findSegment(segments, 100.0), segments.begin() + 2);

  State s;
  // Before the first: end(), but the first segment's start is sampled (held).
  EXPECT_EQ(sampleSegments(segments, 0.0, s), segments.end());
  EXPECT_EQ(s.position[0], 0.0);
  EXPECT_EQ(sampleSegments(segments, 3.0, s), segments.begin() + 1);
  EXPECT_NEAR(s.position[0], 2.0, kEps);
  EXPECT_NEAR(s.velocity[0], 1.0, kEps);
  EXPECT_EQ(sampleSegments(segments, 4.5, s), segments.begin() + 1);  // past its end: held
  EXPECT_NEAR(s.position[0], 3.0, kEps);
  EXPECT_EQ(s.velocity[0], 0.0);
}

}  // namespace
