// The Simulator without ROS: a world alone, a robot added, driven through its controllers,
// every sensor kind read as plain data (computed only when due and wanted), reset, removed.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim_test_support.h"
#include "tianracer_sim/physics/contacts.h"
#include "tianracer_sim/plugins/camera/sim_camera.h"
#include "tianracer_sim/plugins/imu/sim_imu.h"
#include "tianracer_sim/plugins/p3d/sim_p3d.h"
#include "tianracer_sim/plugins/ray/sim_ray.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {
namespace {

RobotModel loadXacro(const std::string& file) {
  test::loadTianracer();  // puts the description on ROS_PACKAGE_PATH for $(find)
  LoadOptions options;
  options.resolver.find_package = [](const std::string& pkg) {
    return pkg == "tianracer_description" ? test::descriptionDir() : std::string();
  };
  return loadRobotModelFile(file, options);
}

RobotSpawn car(RobotModel model) {
  RobotSpawn spawn;
  spawn.name = "tianracer";
  spawn.model = std::move(model);
  spawn.drop_to_ground = true;
  spawn.controllers = test::shippedControllers();
  return spawn;
}

/// A consumer that wants nothing: nothing is computed, every due sample is counted skipped.
class NobodyListens : public SensorListener {
 public:
  SensorOutputs wanted(const SimSensor&, SensorOutputs) override { return 0; }
  void onOutputs(const SimSensor&, SensorOutputs, double) override { ++calls; }
  int calls = 0;
};

TEST(Simulator, AWorldAloneStepsAndARobotArrivesLater) {
  Simulator sim(test::groundWithWall(), {});
  EXPECT_TRUE(sim.robotIds().empty());
  sim.step(100);
  EXPECT_NEAR(sim.time(), 100 * sim.dt(), 1e-12);
  EXPECT_NE(sim.findModel("wall"), kNoModel);
  const ModelId id = sim.addRobot(car(test::loadTianracer()));
  EXPECT_EQ(sim.robotIds(), std::vector<ModelId>{id});
  EXPECT_EQ(sim.findModel("tianracer"), id);
  EXPECT_NEAR(sim.modelState(id).X_WE.translation().z(), test::kSpawnZ, 2e-3);
}

TEST(Simulator, DrivesThroughControllerCommandsAndReportsJointStates) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId id = sim.addRobot(car(test::loadTianracer()));
  const double omega = 0.5 / test::kWheelRadius;  // 0.5 m/s
  ASSERT_TRUE(sim.setCommand(id, "left_rear_wheel_velocity_controller", omega));
  ASSERT_TRUE(sim.setCommand(id, "right_rear_wheel_velocity_controller", omega));
  EXPECT_FALSE(sim.setCommand(id, "no_such_controller", 1.0));
  EXPECT_FALSE(sim.setCommand(id, "left_rear_wheel_velocity_controller", std::nan("")));
  sim.step(1000);
  const EntityState s = sim.modelState(id);
  EXPECT_GT(s.X_WE.translation().x(), 0.3);
  EXPECT_NEAR(s.V_WE.linear.x(), 0.5, 0.05);
  JointStates joints;
  sim.jointStates(id, &joints);
  ASSERT_EQ(joints.name.size(), joints.velocity.size());
  bool found = false;
  for (std::size_t j = 0; j < joints.name.size(); ++j) {
    if (joints.name[j] != "left_rear_wheel_joint") continue;
    found = true;
    EXPECT_NEAR(joints.velocity[j], omega, 0.1 * omega);
  }
  EXPECT_TRUE(found);
}

TEST(Simulator, LoadsStartsStopsAndUnloadsControllersByName) {
  namespace tc = tianracer_control;
  Simulator sim(test::groundWithWall(), {});
  RobotSpawn spawn = car(test::loadTianracer());
  spawn.controllers.clear();  // as after spawn_model: a spawner brings them
  const ModelId id = sim.addRobot(std::move(spawn));
  ControllerManager& manager = sim.controllerManager();
  SimRobot& robot = *sim.robot(id);
  std::vector<std::string> names;
  for (const tc::ControllerSpec& spec : test::shippedControllers()) {
    names.push_back(manager.load(robot, spec).name());
  }
  const double omega = 0.5 / test::kWheelRadius;
  ASSERT_TRUE(sim.setCommand(id, "left_rear_wheel_velocity_controller", omega));
  ASSERT_TRUE(sim.setCommand(id, "right_rear_wheel_velocity_controller", omega));
  sim.step(500);
  EXPECT_LT(sim.modelState(id).X_WE.translation().x(), 0.005);  // loaded, not running

  manager.switchControllers(robot, names, {}, tc::Strictness::kStrict);
  ASSERT_TRUE(sim.setCommand(id, "left_rear_wheel_velocity_controller", omega));
  ASSERT_TRUE(sim.setCommand(id, "right_rear_wheel_velocity_controller", omega));
  sim.step(1000);
  EXPECT_NEAR(sim.modelState(id).V_WE.linear.x(), 0.5, 0.05);

  // Running controllers cannot be unloaded; stopped ones can, and their joints go free.
  EXPECT_THROW(manager.unload(robot, "left_rear_wheel_velocity_controller"), tc::ControllerError);
  manager.switchControllers(robot, {}, {"left_rear_wheel_velocity_controller"}, tc::Strictness::kStrict);
  manager.unload(robot, "left_rear_wheel_velocity_controller");
  EXPECT_FALSE(sim.setCommand(id, "left_rear_wheel_velocity_controller", omega));
  EXPECT_EQ(sim.robot(sim.findModel("wall")), nullptr);  // a world model has no controllers
}

TEST(Simulator, ReadsEverySensorAsPlainData) {
  SimulatorOptions options;
  options.seed = 7;
  Simulator sim(test::groundWithWall(), options);
  const ModelId id = sim.addRobot(car(loadXacro(TEST_DATA_DIR "/urdf/tianracer_imu.xacro")));
  sim.step(200);
  sim.waitFrames();

  // The lidar sees the wall 2 m ahead (its front face at 1.9 m) straight ahead.
  const auto* lidar = dynamic_cast<const SimLidar*>(sim.findSensor(id, "hokuyo_sensor"));
  ASSERT_NE(lidar, nullptr);
  const std::vector<float>& ranges = lidar->ranges();
  ASSERT_EQ(static_cast<int>(ranges.size()), lidar->config().samples);
  EXPECT_NEAR(ranges[ranges.size() / 2], 1.9 - 0.0, 0.1);
  EXPECT_GT(lidar->stat().renders, 0u);

  // The camera and the depth camera rendered frames.
  const auto* camera = dynamic_cast<const SimCamera*>(sim.findSensor(id, "camera1"));
  ASSERT_NE(camera, nullptr);
  EXPECT_EQ(camera->camera().image().size(),
            static_cast<std::size_t>(camera->camera().config().width *
                                     camera->camera().config().height * 3));
  EXPECT_GT(camera->camera().renderCount(), 0u);
  const auto* depth = dynamic_cast<const SimDepthCamera*>(sim.findSensor(id, "real_sense"));
  ASSERT_NE(depth, nullptr);
  EXPECT_GT(depth->camera().renderCount(), 0u);
  const std::vector<float>& d = depth->camera().depth();
  ASSERT_FALSE(d.empty());
  // The wall fills the middle of the depth image at about 1.9 m (the camera sits ahead of
  // base_link; anything within the clip range is fine).
  const float middle = d[d.size() / 2 + depth->camera().config().camera.width / 2];
  EXPECT_TRUE(std::isfinite(middle));
  EXPECT_GT(middle, 1.5f);
  EXPECT_LT(middle, 2.1f);

  // The IMU at rest: specific force +g up; the p3d ground truth at the spawn pose.
  const auto* imu = dynamic_cast<const SimImu*>(sim.findSensor(id, "imu_sensor"));
  ASSERT_NE(imu, nullptr);
  EXPECT_NEAR(imu->reading().linear_acceleration.z(), 9.8, 0.3);
  const auto* p3d = dynamic_cast<const SimP3d*>(sim.findSensor(id, "p3d_base"));
  ASSERT_NE(p3d, nullptr);
  EXPECT_NEAR(p3d->reading().position.x(), sim.modelState(id).X_WE.translation().x(), 1e-3);

  // The bad IMUs of the test model are left out with the reason, the rest runs.
  EXPECT_EQ(sim.findSensor(id, "imu_bad_noise"), nullptr);
  EXPECT_EQ(sim.leftOut(id).count("imu_bad_noise"), 1u);
}

TEST(Simulator, ComputesNothingThatNobodyWants) {
  Simulator sim(test::groundWithWall(), {});
  RobotSpawn spawn = car(test::loadTianracer());
  std::vector<NobodyListens*> listeners;
  spawn.attach = [&](SimSensor& sensor) {
    auto l = std::make_unique<NobodyListens>();
    listeners.push_back(l.get());
    sensor.setListener(std::move(l));
  };
  const ModelId id = sim.addRobot(std::move(spawn));
  sim.step(500);
  sim.waitFrames();
  ASSERT_EQ(listeners.size(), 3u);  // lidar, camera, depth camera
  for (NobodyListens* l : listeners) EXPECT_EQ(l->calls, 0);
  const auto* lidar = dynamic_cast<const SimLidar*>(sim.findSensor(id, "hokuyo_sensor"));
  ASSERT_NE(lidar, nullptr);
  EXPECT_EQ(lidar->stat().renders, 0u);
  EXPECT_GE(lidar->stat().skipped, 19u);  // 40 Hz over 0.5 s
  const auto* camera = dynamic_cast<const SimCamera*>(sim.findSensor(id, "camera1"));
  ASSERT_NE(camera, nullptr);
  EXPECT_EQ(camera->camera().renderCount(), 0u);
}

/// The row's figure; an empty name when there is no such row.
StepProfile::Figure profileFigure(const StepProfile& p, const std::string& name) {
  for (const auto& f : p.figures()) {
    if (f.name == name) return f;
  }
  return StepProfile::Figure();
}

TEST(Simulator, ProfilesEachPartOfTheStepWhenAskedAndTheRunStaysTheSame) {
  StepProfile profile;
  SimulatorOptions options;
  options.profile = &profile;
  Simulator sim(test::groundWithWall(), options);
  const ModelId id = sim.addRobot(car(test::loadTianracer()));
  Simulator plain(test::groundWithWall(), {});
  const ModelId plain_id = plain.addRobot(car(test::loadTianracer()));
  for (const auto& [s, m] : {std::make_pair(&sim, id), std::make_pair(&plain, plain_id)}) {
    ASSERT_TRUE(s->setCommand(m, "left_rear_wheel_velocity_controller", 20.0));
    ASSERT_TRUE(s->setCommand(m, "left_steering_hinge_position_controller", 0.2));
  }
  sim.step(300);
  plain.step(300);
  sim.waitFrames();
  plain.waitFrames();
  // Timing changes nothing of the run.
  EXPECT_EQ(sim.modelState(id).X_WE.matrix(), plain.modelState(plain_id).X_WE.matrix());

  EXPECT_EQ(profile.steps(), 300u);
  for (const char* row : {StepProfile::kStep, StepProfile::kBullet, StepProfile::kControllers,
                          "contacts: scan of the step's manifolds"}) {
    const StepProfile::Figure f = profileFigure(profile, row);
    EXPECT_EQ(f.name, row);
    EXPECT_EQ(f.calls, 300u) << row;
    EXPECT_GT(f.seconds, 0.0) << row;
  }
  // Each sensor's cast or frame is counted where it happens.
  const auto* lidar = sim.findSensor(id, "hokuyo_sensor");
  ASSERT_NE(lidar, nullptr);
  EXPECT_EQ(profileFigure(profile, "sensor lidar: sample (cast, measure)").calls,
            lidar->stat().renders);
  EXPECT_EQ(profileFigure(profile, "sensor lidar: update").calls, 300u);
  const auto* camera = dynamic_cast<const SimCamera*>(sim.findSensor(id, "camera1"));
  const auto* depth = dynamic_cast<const SimDepthCamera*>(sim.findSensor(id, "real_sense"));
  ASSERT_NE(camera, nullptr);
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(profileFigure(profile, "frame worker: camera render").calls,
            camera->camera().renderCount());
  EXPECT_EQ(profileFigure(profile, "frame worker: renders / glReadPixels").calls,
            camera->camera().renderCount() + depth->camera().renderCount());
  EXPECT_GT(profileFigure(profile, "frame worker: renders / GL draw to glFinish").seconds, 0.0);
  EXPECT_NE(profile.table().find("step outside Bullet"), std::string::npos);
}

TEST(Simulator, TracksContactsOnlyWhileAskedAndCountsOneInProgressAsNewWhenResumed) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId id = sim.addRobot(car(test::loadTianracer()));
  EXPECT_TRUE(sim.contactTracking());  // on by default (the Python environment counts them)
  sim.setContactTracking(false);
  const double omega = 1.0 / test::kWheelRadius;  // 1 m/s into the wall (its face at 1.9 m)
  ASSERT_TRUE(sim.setCommand(id, "left_rear_wheel_velocity_controller", omega));
  ASSERT_TRUE(sim.setCommand(id, "right_rear_wheel_velocity_controller", omega));
  sim.step(3000);
  // The car is against the wall (its wheels still turning), and nothing was counted.
  const auto* robot = sim.robot(id);
  ASSERT_NE(robot, nullptr);
  std::vector<RobotContact> now;
  sim.robotContacts(id, &now);
  ASSERT_FALSE(now.empty()) << "the car should touch the wall at x = "
                            << sim.modelState(id).X_WE.translation().x();
  EXPECT_EQ(sim.contactCount(id), 0u);
  EXPECT_TRUE(sim.contacts().due().empty());
  // Tracked again: the contact in progress is new, counted and due at once.
  sim.setContactTracking(true);
  sim.step(1);
  EXPECT_GE(sim.contactCount(id), 1u);
  EXPECT_FALSE(sim.contacts().due().empty());
  // Off again: the due list goes, the count stays.
  const std::uint64_t counted = sim.contactCount(id);
  sim.setContactTracking(false);
  EXPECT_TRUE(sim.contacts().due().empty());
  sim.step(10);
  EXPECT_EQ(sim.contactCount(id), counted);
}

TEST(Simulator, DisabledSensorsAreLeftOutWithTheReason) {
  Simulator sim(test::groundWithWall(), {});
  RobotSpawn spawn = car(test::loadTianracer());
  spawn.disabled_sensors = {"camera", "depth"};
  const ModelId id = sim.addRobot(std::move(spawn));
  EXPECT_NE(sim.findSensor(id, "hokuyo_sensor"), nullptr);
  EXPECT_EQ(sim.findSensor(id, "camera1"), nullptr);
  EXPECT_EQ(sim.findSensor(id, "real_sense"), nullptr);
  EXPECT_EQ(sim.leftOut(id).at("camera1"), kDisabledBySensorList);
}

TEST(Simulator, ResetBringsTimeAndTheRobotBack) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId id = sim.addRobot(car(test::loadTianracer()));
  const Eigen::Vector3d spawn = sim.modelState(id).X_WE.translation();
  sim.setCommand(id, "left_rear_wheel_velocity_controller", 20.0);
  sim.setCommand(id, "right_rear_wheel_velocity_controller", 20.0);
  sim.step(500);
  ASSERT_GT((sim.modelState(id).X_WE.translation() - spawn).norm(), 0.1);
  sim.resetSimulation();
  EXPECT_EQ(sim.time(), 0.0);
  EXPECT_LT((sim.modelState(id).X_WE.translation() - spawn).norm(), 1e-9);
  // Sensors run again from time 0 (their schedules restarted).
  const SimSensor* lidar = sim.findSensor(id, "hokuyo_sensor");
  const std::uint64_t before = lidar->stat().renders;
  sim.step(30);
  EXPECT_GT(lidar->stat().renders, before);
}

TEST(Simulator, RemovingARobotTakesItsSensorsAndNameAway) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId id = sim.addRobot(car(test::loadTianracer()));
  sim.step(50);
  sim.removeModel("tianracer");
  EXPECT_TRUE(sim.sensors().empty());
  EXPECT_EQ(sim.findModel("tianracer"), kNoModel);
  EXPECT_EQ(sim.robot(id), nullptr);
  sim.step(50);
  const ModelId again = sim.addRobot(car(test::loadTianracer()));
  EXPECT_NE(again, id);  // ids are never reused
  EXPECT_THROW(sim.removeModel("nothing"), std::runtime_error);
}

TEST(Simulator, LinkDataOfWorldModelsToo) {
  Simulator sim(test::groundWithWall(), {});
  const ModelId wall = sim.findModel("wall");
  ASSERT_NE(wall, kNoModel);
  EXPECT_NEAR(sim.linkPose({wall, "link"}).translation().x(), 2.0, 1e-12);
  LinkState state;
  ASSERT_TRUE(sim.linkState({wall, "link"}, &state));
  EXPECT_EQ(state.v_W.norm(), 0.0);
  std::vector<LinkContact> contacts(1);
  sim.linkContacts({wall, "link"}, &contacts);
  EXPECT_TRUE(contacts.empty());
}

TEST(Simulator, LockstepDecidesWhichStepsWait) {
  Simulator sim(test::groundWithWall(), {});
  sim.setLockstep(true, 0.02, false, 0.02);
  int replies = 0, ticks = 0;
  for (int k = 0; k < 100; ++k) {
    const StepWaits w = sim.advance();
    replies += w.replies;
    ticks += w.ticks;
  }
  EXPECT_EQ(replies, 5);  // 0.1 s at one per 0.02 s, the first one period after the start
  EXPECT_EQ(ticks, 0);
}

TEST(Simulator, RejectsAStepOutOfRange) {
  SimulatorOptions options;
  options.max_step_size = 0.5;
  EXPECT_THROW(Simulator(test::groundWithWall(), options), std::invalid_argument);
}

}  // namespace
}  // namespace tianracer_sim

namespace tianracer_sim {
namespace {

// What a cache of the model list (gazebo_states' message slots) compares: a model removed and
// another added, the count unchanged, is still a change.
TEST(Simulator, ModelsVersionChangesWithEveryAddAndRemove) {
  Simulator sim(test::groundWithWall(), {});
  const std::uint64_t v0 = sim.modelsVersion();
  sim.addRobot(car(test::loadTianracer()));
  const std::uint64_t v1 = sim.modelsVersion();
  EXPECT_NE(v1, v0);
  sim.removeModel("tianracer");
  RobotSpawn other = car(test::loadTianracer());
  other.name = "other";
  sim.addRobot(std::move(other));
  EXPECT_EQ(sim.robotIds().size(), 1u);
  EXPECT_NE(sim.modelsVersion(), v1);
  const std::uint64_t v2 = sim.modelsVersion();
  sim.step(1);
  EXPECT_EQ(sim.modelsVersion(), v2);  // stepping is no change
}

}  // namespace
}  // namespace tianracer_sim
