// FrameWorker: jobs run on one background thread, in submission order, one in flight; the
// scene snapshot copies poses only while the scene keeps its shape.
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/sim/frame_worker.h"

namespace tianracer_sim {
namespace {

struct Job {
  int value = 0;
};

TEST(FrameWorker, RunsJobsInOrderOnItsOwnThreadOneAtATime) {
  std::vector<int> seen;  // written by the worker only
  std::atomic<int> running{0};
  std::atomic<int> max_running{0};
  std::thread::id worker_id;
  {
    FrameWorker<Job> worker([&](Job& job) {
      const int now = ++running;
      max_running = std::max(max_running.load(), now);
      worker_id = std::this_thread::get_id();
      std::this_thread::sleep_for(std::chrono::microseconds(200));
      seen.push_back(job.value);
      --running;
    });
    for (int i = 0; i < 20; ++i) {
      worker.submit([&](Job& job) {
        EXPECT_EQ(running.load(), 0);  // fill() runs while the worker is idle
        job.value = i;
      });
    }
    worker.wait();
    EXPECT_EQ(seen.size(), 20u);
  }
  EXPECT_NE(worker_id, std::this_thread::get_id());
  EXPECT_EQ(max_running.load(), 1);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(seen[i], i);
}

TEST(FrameWorker, DestructionFinishesTheJobInFlight) {
  std::atomic<bool> done{false};
  {
    FrameWorker<Job> worker([&](Job&) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      done = true;
    });
    worker.submit([](Job&) {});
  }
  EXPECT_TRUE(done.load());
}

TEST(FrameWorker, SnapshotCopiesPosesOrTheWholeScene) {
  Scene scene;
  scene.addBody(SceneBody{"a::link", "a", false, Eigen::Isometry3d::Identity()});
  scene.items.push_back(SceneItem{});
  Scene copy;
  snapshotScene(scene, &copy);
  ASSERT_EQ(copy.bodies.size(), 1u);
  EXPECT_EQ(copy.bodies[0].name, "a::link");

  scene.bodies[0].X_WB.translation() = Eigen::Vector3d(1, 2, 3);
  snapshotScene(scene, &copy);
  EXPECT_EQ(copy.bodies[0].X_WB.translation(), Eigen::Vector3d(1, 2, 3));

  scene.addBody(SceneBody{"b::link", "b", false, Eigen::Isometry3d::Identity()});  // a robot more
  snapshotScene(scene, &copy);
  ASSERT_EQ(copy.bodies.size(), 2u);
  EXPECT_EQ(copy.bodies[1].name, "b::link");
}

}  // namespace
}  // namespace tianracer_sim
