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

TEST(Pacer, AsFastAsPossibleNeverWaits) {
  FakeWall wall;
  Pacer pacer = wall.make();
  for (int i = 0; i < 10; ++i) {
    pacer.beginStep(i * 0.01);
    pacer.endStep((i + 1) * 0.01, 0.0);
  }
  EXPECT_TRUE(wall.served.empty());
  EXPECT_TRUE(wall.slept.empty());
}

TEST(Pacer, WaitsUntilTheStepsWallTimeServingFirstThenSleeping) {
  FakeWall wall;
  wall.serve_returns_after = 0.004;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  wall.advance(0.002);  // the step took 2 ms of wall time
  pacer.endStep(0.01, 1.0);
  ASSERT_EQ(wall.served.size(), 1u);
  EXPECT_NEAR(wall.served[0], 0.008, 1e-9);
  ASSERT_EQ(wall.slept.size(), 1u);
  EXPECT_NEAR(wall.slept[0], 0.004, 1e-9);  // what serve() left
  EXPECT_NEAR(std::chrono::duration<double>(wall.now.time_since_epoch()).count(), 0.01, 1e-9);
}

TEST(Pacer, TwiceRealTimeWaitsHalfTheSimTime) {
  FakeWall wall;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  for (int i = 1; i <= 4; ++i) pacer.endStep(i * 0.1, 2.0);
  EXPECT_NEAR(std::chrono::duration<double>(wall.now.time_since_epoch()).count(), 0.2, 1e-9);
  EXPECT_TRUE(wall.slept.empty());
}

TEST(Pacer, FarBehindItDoesNotRaceToCatchUpButMeasuresAgain) {
  FakeWall wall;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  wall.advance(0.8);  // a step that took 0.8 s of wall time for 0.1 s of sim time
  pacer.endStep(0.1, 1.0);
  EXPECT_TRUE(wall.served.empty());
  pacer.beginStep(0.1);  // measured from here: the next 0.1 s waits 0.1 s
  pacer.endStep(0.2, 1.0);
  ASSERT_EQ(wall.served.size(), 1u);
  EXPECT_NEAR(wall.served[0], 0.1, 1e-9);
}

TEST(Pacer, SlightlyBehindItCatchesUpWithoutWaiting) {
  FakeWall wall;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  wall.advance(0.3);
  pacer.endStep(0.1, 1.0);  // 0.2 s behind
  pacer.beginStep(0.1);
  pacer.endStep(0.2, 1.0);  // still 0.1 s behind: no wait, no new measure
  pacer.beginStep(0.2);
  pacer.endStep(0.45, 1.0);  // 0.15 s ahead of the first measure
  ASSERT_EQ(wall.served.size(), 1u);
  EXPECT_NEAR(wall.served[0], 0.15, 1e-9);
}

TEST(Pacer, AChangedFactorMeasuresFromThatStep) {
  FakeWall wall;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  pacer.endStep(1.0, 1.0);  // waits 1 s
  pacer.beginStep(1.0);
  pacer.endStep(2.0, 0.5);  // from here on half speed: 2.0 is now, 3.0 two seconds later
  pacer.beginStep(2.0);
  pacer.endStep(3.0, 0.5);
  ASSERT_EQ(wall.served.size(), 2u);
  EXPECT_NEAR(wall.served[0], 1.0, 1e-9);
  EXPECT_NEAR(wall.served[1], 2.0, 1e-9);
}

TEST(Pacer, RestartMeasuresFromTheNextStepsStart) {
  FakeWall wall;
  Pacer pacer = wall.make();
  pacer.beginStep(0.0);
  pacer.endStep(0.1, 1.0);
  wall.advance(5.0);  // paused for 5 s
  pacer.restart();
  pacer.beginStep(0.1);
  pacer.endStep(0.2, 1.0);  // 0.1 s after the restart, not 4.9 s behind
  ASSERT_EQ(wall.served.size(), 2u);
  EXPECT_NEAR(wall.served[1], 0.1, 1e-9);
}

}  // namespace
}  // namespace tianracer_sim
