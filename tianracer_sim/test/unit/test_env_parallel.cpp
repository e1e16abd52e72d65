// The vector environment's thread set: every index once per run, exceptions carried back.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "tianracer_sim/env/parallel.h"

namespace tianracer_sim {
namespace {

TEST(ParallelFor, EachIndexOncePerRunAcrossManyRuns) {
  ParallelFor pool(3);
  EXPECT_EQ(pool.threads(), 3);
  for (int run = 0; run < 200; ++run) {
    const int n = 1 + run % 9;
    std::vector<std::atomic<int>> hits(n);
    pool.run(n, [&](int i) { ++hits[i]; });
    for (int i = 0; i < n; ++i) ASSERT_EQ(hits[i].load(), 1) << "run " << run << " index " << i;
  }
}

TEST(ParallelFor, OneThreadRunsOnTheCaller) {
  ParallelFor pool(1);
  int sum = 0;
  pool.run(5, [&](int i) { sum += i; });
  EXPECT_EQ(sum, 10);
}

TEST(ParallelFor, AnExceptionComesBackAfterAllCallsEnded) {
  ParallelFor pool(2);
  std::atomic<int> done{0};
  EXPECT_THROW(pool.run(6,
                        [&](int i) {
                          if (i == 2) throw std::runtime_error("bad");
                          ++done;
                        }),
               std::runtime_error);
  EXPECT_EQ(done.load(), 5);
  pool.run(2, [&](int) { ++done; });  // usable afterwards
  EXPECT_EQ(done.load(), 7);
}

}  // namespace
}  // namespace tianracer_sim
