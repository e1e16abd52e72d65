// The real-time pace: how long the node waits after each step, on a clock the test moves.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "tianracer_sim/common/pacer.h"

namespace tianracer_sim {
namespace {

/// A wall clock that only moves when a wait or the test moves it.
struct FakeWall {
  Pacer::Clock::time_point now{};
  double serve_returns_after = 1e9;  // serve() gives up after this long, as a callback queue does
  std::vector<double> served, slept;

  void advance(double s) {
    now += std::chrono::duration_cast<Pacer::Clock::duration>(std::chrono::duration<double>(s));
  }
  Pacer make() {
    Pacer::Hooks h;
    h.serve = [this](double s) {
      served.push_back(s);
      advance(std::min(s, serve_returns_after));
    };
    h.sleep = [this](double s) {
      slept.push_back(s);
      advance(s);
    };
    h.now = [this] { return now; };
    return Pacer(std::move(h));
  }
};

/// One step of the node's loop: from sim time `from` to `to` at `factor`, the step itself
/// taking `took` seconds of wall time.
void step(Pacer& pacer, FakeWall& wall, double from, double to, double factor, double took = 0.0) {
  pacer.beginStep(from);
  wall.advance(took);
  pacer.endStep(to, factor);
}

double wallSeconds(const FakeWall& wall) {
  return std::chrono::duration<double>(wall.now.time_since_epoch()).count();
}

TEST(Pacer, AsFastAsPossibleNeverWaits) {
  FakeWall wall;
  Pacer pacer = wall.make();
  for (int i = 0; i < 10; ++i) {
    step(pacer, wall, i * 0.01, (i + 1) * 0.01, 0.0);
  }
  EXPECT_TRUE(wall.served.empty());
  EXPECT_TRUE(wall.slept.empty());
}

TEST(Pacer, WaitsUntilTheStepsWallTimeServingFirstThenSleeping) {
  FakeWall wall;
  wall.serve_returns_after = 0.004;
  Pacer pacer = wall.make();
  step(pacer, wall, 0.0, 0.01, 1.0, 0.002);  // the step took 2 ms of wall time
  ASSERT_EQ(wall.served.size(), 1u);
  EXPECT_NEAR(wall.served[0], 0.008, 1e-9);
  ASSERT_EQ(wall.slept.size(), 1u);
  EXPECT_NEAR(wall.slept[0], 0.004, 1e-9);  // what serve() left
  EXPECT_NEAR(wallSeconds(wall), 0.01, 1e-9);
}

TEST(Pacer, TwiceRealTimeWaitsHalfTheSimTime) {
  FakeWall wall;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  for (int i = 1; i <= 4; ++i) pacer.endStep(i * 0.1, 2.0);
  EXPECT_NEAR(wallSeconds(wall), 0.2, 1e-9);
  EXPECT_TRUE(wall.slept.empty());
}

TEST(Pacer, FarBehindItDoesNotRaceToCatchUpButMeasuresAgain) {
  FakeWall wall;
  Pacer pacer = wall.make();
  step(pacer, wall, 0.0, 0.1, 1.0, 0.8);  // 0.8 s of wall time for 0.1 s of sim time
  EXPECT_TRUE(wall.served.empty());
  step(pacer, wall, 0.1, 0.2, 1.0);  // measured from its start: 0.1 s waits 0.1 s
  ASSERT_EQ(wall.served.size(), 1u);
  EXPECT_NEAR(wall.served[0], 0.1, 1e-9);
}

TEST(Pacer, SlightlyBehindItCatchesUpWithoutWaiting) {
  FakeWall wall;
  Pacer pacer = wall.make();
  step(pacer, wall, 0.0, 0.1, 1.0, 0.3);  // 0.2 s behind
  step(pacer, wall, 0.1, 0.2, 1.0);  // still 0.1 s behind: no wait, no new measure
  step(pacer, wall, 0.2, 0.45, 1.0);  // 0.15 s ahead of the first measure
  ASSERT_EQ(wall.served.size(), 1u);
  EXPECT_NEAR(wall.served[0], 0.15, 1e-9);
}

TEST(Pacer, AChangedFactorMeasuresFromThatStep) {
  FakeWall wall;
  Pacer pacer = wall.make();
  step(pacer, wall, 0.0, 1.0, 1.0);  // waits 1 s
  step(pacer, wall, 1.0, 2.0, 0.5);  // from here on half speed: 2.0 is now, 3.0 two seconds later
  step(pacer, wall, 2.0, 3.0, 0.5);
  ASSERT_EQ(wall.served.size(), 2u);
  EXPECT_NEAR(wall.served[0], 1.0, 1e-9);
  EXPECT_NEAR(wall.served[1], 2.0, 1e-9);
}

TEST(Pacer, RestartMeasuresFromTheNextStepsStart) {
  FakeWall wall;
  Pacer pacer = wall.make();
  step(pacer, wall, 0.0, 0.1, 1.0);
  wall.advance(5.0);  // paused for 5 s
  pacer.restart();
  step(pacer, wall, 0.1, 0.2, 1.0);  // 0.1 s after the restart, not 4.9 s behind
  ASSERT_EQ(wall.served.size(), 2u);
  EXPECT_NEAR(wall.served[1], 0.1, 1e-9);
}

}  // namespace
}  // namespace tianracer_sim
