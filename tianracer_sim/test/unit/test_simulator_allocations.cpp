// A warm step allocates nothing (issue 27): the controllers, the physics, the contact tracking
// and the lidar's cast reuse their buffers from one step to the next. This binary counts every
// operator new and every Bullet aligned allocation (as physics_bench does) over 1000 steps of
// a car that keeps touching something: a wall it drives against, a free box it pushes. The
// one allocation a lidar cast makes is Embree's: rtcCommitScene, when the car's bodies moved,
// allocates inside libembree3 (found with a breakpoint on this counter; about one per cast).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <LinearMath/btAlignedAllocator.h>
#pragma GCC diagnostic pop

#include "sim_test_support.h"
#include "tianracer_sim/physics/contacts.h"
#include "tianracer_sim/simulator/simulator.h"

namespace {
std::atomic<unsigned long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
// The whole replaceable set, so that every form pairs through malloc and free. Without them
// the library's forms (ASan's own in a Sanitize build) allocate what ours free:
// std::stable_sort's nothrow buffer was "operator new vs free" under AddressSanitizer. The
// default forms call operator new(size_t), so the count is the same.
void* operator new[](std::size_t n) { return ::operator new(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(n ? n : 1);
}
void* operator new[](std::size_t n, const std::nothrow_t& tag) noexcept {
  return ::operator new(n, tag);
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }

namespace tianracer_sim {
namespace {

void* countingAlignedAlloc(size_t size, int alignment) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  void* p = nullptr;
  if (posix_memalign(&p, static_cast<size_t>(alignment < 16 ? 16 : alignment), size) != 0) return nullptr;
  return p;
}
void countingAlignedFree(void* p) { std::free(p); }

/// Everything due is wanted (a subscriber on every topic).
class EveryOutput : public SensorListener {
 public:
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override { return due; }
  void onOutputs(const SimSensor&, SensorOutputs, double) override {}
};

/// Allocations per step over `steps` steps of `sim`, after `warm` steps.
double allocationsPerStep(Simulator& sim, int warm, int steps) {
  sim.step(warm);
  const unsigned long before = g_allocations.load();
  sim.step(steps);
  return static_cast<double>(g_allocations.load() - before) / steps;
}

ModelId addCar(Simulator& sim, std::vector<std::string> disabled, double speed) {
  RobotSpawn spawn;
  spawn.name = "tianracer";
  spawn.model = test::loadTianracer();
  spawn.drop_to_ground = true;
  spawn.controllers = test::shippedControllers();
  spawn.disabled_sensors = std::move(disabled);
  spawn.attach = [](SimSensor& s) { s.setListener(std::make_unique<EveryOutput>()); };
  const ModelId id = sim.addRobot(std::move(spawn));
  const double omega = speed / test::kWheelRadius;
  EXPECT_TRUE(sim.setCommand(id, "left_rear_wheel_velocity_controller", omega));
  EXPECT_TRUE(sim.setCommand(id, "right_rear_wheel_velocity_controller", omega));
  return id;
}

bool touching(Simulator& sim, ModelId id) {
  std::vector<RobotContact> now;
  sim.robotContacts(id, &now);
  return !now.empty();
}

class Allocations : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { btAlignedAllocSetCustomAligned(countingAlignedAlloc, countingAlignedFree); }
};

TEST_F(Allocations, NonePerStepForTheCarAgainstAWallWithItsContactsTracked) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId id = addCar(sim, {"ray", "camera", "depth"}, 1.0);
  ASSERT_TRUE(sim.contactTracking());
  const double per_step = allocationsPerStep(sim, 2500, 1000);
  EXPECT_TRUE(touching(sim, id)) << "the car should be against the wall";
  EXPECT_GT(sim.contactCount(id), 0u);
  EXPECT_EQ(per_step, 0.0);
}

TEST_F(Allocations, NonePerStepForTheCarPushingAFreeBox) {
  Simulator sim(loadWorldFile(std::string(TEST_DATA_DIR) + "/worlds/free_box.world"), {});
  const ModelId id = addCar(sim, {"ray", "camera", "depth"}, 0.5);
  const double per_step = allocationsPerStep(sim, 2000, 1000);
  EXPECT_TRUE(touching(sim, id)) << "the car should push the box";
  EXPECT_GT(sim.modelState(sim.findModel("crate")).X_WE.translation().x(), 0.9);  // it moved
  EXPECT_EQ(per_step, 0.0);
}

TEST_F(Allocations, NoneOfOursPerLidarCastOnlyEmbreesSceneCommit) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId id = addCar(sim, {"camera", "depth"}, 0.3);
  const SimSensor* lidar = sim.findSensor(id, "hokuyo_sensor");
  ASSERT_NE(lidar, nullptr);
  sim.step(500);
  const std::uint64_t casts_before = lidar->stat().renders;
  const double per_step = allocationsPerStep(sim, 0, 1000);
  const double casts = static_cast<double>(lidar->stat().renders - casts_before);
  EXPECT_GE(casts, 39.0);  // 40 Hz over 1 s: it cast
  // Embree's commit: about one per cast; anything of ours per cast would make it two or more.
  EXPECT_LE(per_step * 1000.0, 1.25 * casts);
}

}  // namespace
}  // namespace tianracer_sim
