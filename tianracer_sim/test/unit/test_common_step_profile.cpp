// The step profile: rows by name, lock-free additions from two threads, the per-step table.
#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <thread>

#include "tianracer_sim/common/step_profile.h"

namespace tianracer_sim {
namespace {

using std::chrono::microseconds;

const StepProfile::Figure* find(const std::vector<StepProfile::Figure>& figures,
                                const std::string& name) {
  for (const auto& f : figures) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

TEST(StepProfile, RowsKeepTheirFirstPlaceAndSumTheirCalls) {
  StepProfile p;
  const int a = p.row("a");
  const int b = p.row("a / part");
  EXPECT_EQ(p.row("a"), a);
  EXPECT_NE(a, b);
  for (int i = 0; i < 4; ++i) {
    p.countStep();
    p.add(a, microseconds(10));
    p.add(b, microseconds(3));
  }
  const auto figures = p.figures();
  ASSERT_EQ(figures.size(), 2u);
  EXPECT_EQ(figures[0].name, "a");
  EXPECT_EQ(figures[0].calls, 4u);
  EXPECT_NEAR(figures[0].seconds, 40e-6, 1e-12);
  EXPECT_FALSE(figures[0].part);
  EXPECT_TRUE(figures[1].part);
  EXPECT_EQ(p.steps(), 4u);
  p.reset();
  EXPECT_EQ(p.steps(), 0u);
  EXPECT_EQ(p.figures()[0].calls, 0u);
  EXPECT_EQ(p.figures().size(), 2u);  // the rows stay
}

TEST(StepProfile, TableGivesMicrosecondsPerStepAndTheTimeOutsideBullet) {
  StepProfile p;
  const int step = p.row(StepProfile::kStep);
  const int between = p.row(std::string(StepProfile::kBetweenSteps) + "callbacks");
  const int bullet = p.row(StepProfile::kBullet);
  const int unused = p.row("never called");
  (void)unused;
  for (int i = 0; i < 10; ++i) {
    p.countStep();
    p.add(step, microseconds(50));
    p.add(between, microseconds(2));
    p.add(bullet, microseconds(40));
  }
  const std::string table = p.table();
  EXPECT_NE(table.find("step (all of it)"), std::string::npos) << table;
  EXPECT_NE(table.find("50.000"), std::string::npos) << table;
  EXPECT_EQ(table.find("never called"), std::string::npos) << table;
  // 50 + 2 - 40 us per step.
  const auto line = table.substr(table.find("step outside Bullet"));
  EXPECT_NE(line.find("12.000"), std::string::npos) << table;
  EXPECT_NE(table.find("10 steps"), std::string::npos) << table;
}

TEST(StepProfile, ANullProfileTimesNothingAndARowPastTheLastIsOther) {
  { StepProfile::Scope nothing(nullptr, 3); }
  EXPECT_EQ(profileRow(nullptr, "x"), -1);
  StepProfile p;
  for (int i = 0; i < StepProfile::kMaxRows + 5; ++i) p.row("row " + std::to_string(i));
  const auto figures = p.figures();
  ASSERT_EQ(static_cast<int>(figures.size()), StepProfile::kMaxRows);
  EXPECT_EQ(figures.back().name, "other");
  EXPECT_EQ(p.row("row 300"), StepProfile::kMaxRows - 1);
}

TEST(StepProfile, TwoThreadsAddToOneRowWithoutLosingACall) {
  StepProfile p;
  const int r = p.row("shared");
  auto work = [&] {
    for (int i = 0; i < 100000; ++i) p.add(r, std::chrono::nanoseconds(1));
  };
  std::thread other(work);
  work();
  other.join();
  EXPECT_EQ(find(p.figures(), "shared")->calls, 200000u);
  EXPECT_NEAR(find(p.figures(), "shared")->seconds, 200000e-9, 1e-12);
}

}  // namespace
}  // namespace tianracer_sim
