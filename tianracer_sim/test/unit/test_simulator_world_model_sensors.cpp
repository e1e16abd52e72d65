// Sensors on world models (test/data/worlds/world_model_sensors.world): made with the robots'
// sensor registry from the world file and from addWorldModel (spawn_sdf_model), they see the
// other models, follow a falling model, and go with their model.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/camera/sim_camera.h"
#include "tianracer_sim/plugins/p3d/sim_p3d.h"
#include "tianracer_sim/plugins/ray/sim_ray.h"
#include "tianracer_sim/simulator/simulator.h"

namespace tianracer_sim {
namespace {

const std::string kWorld = std::string(TEST_DATA_DIR) + "/worlds/world_model_sensors.world";

/// Counts what each attached world-model sensor is handed.
class Counter : public SensorListener {
 public:
  explicit Counter(int* calls) : calls_(calls) {}
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override { return due; }
  void onOutputs(const SimSensor&, SensorOutputs, double) override { ++*calls_; }

 private:
  int* calls_;
};

TEST(WorldModelSensors, AStaticModelsLidarAndCamerasSeeAnotherModel) {
  std::vector<std::string> attached;
  int calls = 0;
  SimulatorOptions options;
  std::vector<std::string> warnings;
  options.log.warn = [&](const std::string& w) { warnings.push_back(w); };
  Simulator sim(loadWorldFile(kWorld), options);
  // The publishers' owner comes after the Simulator (the ROS node is given one built before it).
  sim.attachWorldSensors([&](SimSensor& s) {
    attached.push_back(s.modelName() + "/" + s.name());
    s.setListener(std::make_unique<Counter>(&calls));
  });
  EXPECT_EQ(attached, (std::vector<std::string>{"sensor_post/post_lidar", "sensor_post/post_camera",
                                                "sensor_post/post_depth", "faller/faller_beam",
                                                "faller/faller_bumper", "faller/faller_truth"}));
  // The model plugin nobody simulates is reported with its place.
  int reported = 0;
  for (const std::string& w : warnings) {
    reported += w.find("world_model_sensors.world:") != std::string::npos &&
                w.find("model 'target': plugin 'mover' (libsome_model_plugin.so) is not simulated") !=
                    std::string::npos;
  }
  EXPECT_EQ(reported, 1) << ::testing::PrintToString(warnings);
  const ModelId post = sim.findModel("sensor_post");
  ASSERT_NE(post, kNoModel);
  EXPECT_TRUE(sim.leftOut(post).empty());
  sim.step(250);
  sim.waitFrames();
  EXPECT_GT(calls, 0);

  // The lidar at the origin, 0.5 m up, sees the box's near face 2.5 m ahead, nothing behind.
  const auto* lidar = dynamic_cast<const SimLidar*>(sim.findSensor(post, "post_lidar"));
  ASSERT_NE(lidar, nullptr);
  EXPECT_EQ(lidar->link().model, post);
  EXPECT_EQ(lidar->link().link, "head");
  const std::vector<float>& ranges = lidar->ranges();
  ASSERT_EQ(ranges.size(), 181u);
  EXPECT_NEAR(ranges[90], 2.5, 0.05);
  EXPECT_FALSE(ranges[0] < 9.0f);  // +-90 degrees: open floor, nothing within range
  EXPECT_GT(lidar->stat().count, 0u);

  // The camera sees the red box in the middle of its image, the sky above it.
  const auto* camera = dynamic_cast<const SimCamera*>(sim.findSensor(post, "post_camera"));
  ASSERT_NE(camera, nullptr);
  const CameraConfig& c = camera->camera().config();
  const std::vector<uint8_t>& image = camera->camera().image();
  ASSERT_EQ(image.size(), static_cast<std::size_t>(c.width * c.height * 3));
  const std::size_t middle = (static_cast<std::size_t>(c.height / 2) * c.width + c.width / 2) * 3;
  EXPECT_GT(image[middle], 2 * image[middle + 1]);  // red over green
  EXPECT_GT(image[middle], 2 * image[middle + 2]);  // red over blue
  const std::size_t top = (static_cast<std::size_t>(2) * c.width + c.width / 2) * 3;
  EXPECT_GT(image[top + 2], image[top]);  // sky: blue over red

  // The depth camera measures the same 2.5 m.
  const auto* depth = dynamic_cast<const SimDepthCamera*>(sim.findSensor(post, "post_depth"));
  ASSERT_NE(depth, nullptr);
  const int w = depth->camera().config().camera.width, h = depth->camera().config().camera.height;
  const std::vector<float>& d = depth->camera().depth();
  ASSERT_EQ(d.size(), static_cast<std::size_t>(w * h));
  EXPECT_NEAR(d[static_cast<std::size_t>(h / 2) * w + w / 2], 2.5, 0.05);
}

TEST(WorldModelSensors, AFallingModelsSensorMovesWithIt) {
  Simulator sim(loadWorldFile(kWorld), {});
  const ModelId faller = sim.findModel("faller");
  ASSERT_NE(faller, kNoModel);
  const auto* beam = dynamic_cast<const SimLidar*>(sim.findSensor(faller, "faller_beam"));
  ASSERT_NE(beam, nullptr);
  sim.step(1);
  ASSERT_EQ(beam->ranges().size(), 1u);
  EXPECT_NEAR(beam->ranges()[0], 2.0, 0.02);  // the ground 2 m below the box's centre's level
  const auto* truth = dynamic_cast<const SimP3d*>(sim.findSensor(faller, "faller_truth"));
  ASSERT_NE(truth, nullptr);
  EXPECT_NEAR(truth->reading().position.z(), 2.0, 1e-3);
  sim.step(300);  // 0.3 s of free fall: z = 2 - g t^2 / 2, v = -g t
  EXPECT_NEAR(truth->reading().position.z(), 2.0 - 0.5 * 9.8 * 0.09, 0.02);
  EXPECT_NEAR(truth->reading().linear.z(), -9.8 * 0.3, 0.05);
  EXPECT_NEAR(beam->ranges()[0], truth->reading().position.z(), 0.02);
  sim.step(1700);  // 2 s: fallen, resting on its face
  EXPECT_NEAR(sim.modelState(faller).X_WE.translation().z(), 0.1, 0.02);
  EXPECT_NEAR(beam->ranges()[0], 0.1, 0.02);
}

TEST(WorldModelSensors, ASpawnedModelBringsItsSensorsAndTakesThemAway) {
  std::vector<std::string> errors;
  SimulatorOptions options;
  options.log.error = [&](const std::string& e) { errors.push_back(e); };
  Simulator sim(loadWorldFile(kWorld), options);
  const std::size_t before = sim.sensors().size();
  ModelDescription spawned = loadModelString(
      "<sdf version='1.6'><model name='spawned'><static>true</static><link name='l'>"
      "<sensor type='ray' name='side'><update_rate>10</update_rate><ray><scan><horizontal>"
      "<samples>3</samples><min_angle>-0.01</min_angle><max_angle>0.01</max_angle></horizontal>"
      "</scan><range><min>0.1</min><max>10</max></range></ray>"
      "<plugin name='p' filename='libgazebo_ros_laser.so'><topicName>side</topicName>"
      "<frameName>side</frameName></plugin></sensor>"
      "<sensor type='ray' name='bad'><update_rate>-2</update_rate></sensor>"
      "</link></model></sdf>",
      "spawn_sdf_model 'spawned'", ".");
  // 1.5 m to the right of the box, looking at its side (face at y = 0.5, 1 m away).
  spawned.X_WM = Eigen::Translation3d(3.0, -1.5, 0.5) *
                 Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());
  const ModelId id = sim.addWorldModel(std::move(spawned));
  ASSERT_EQ(sim.sensors().size(), before + 1);
  EXPECT_EQ(sim.findSensor(id, "bad"), nullptr);  // a bad rate: left out, the model is there
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "model 'spawned': sensor 'bad' left out: spawn_sdf_model 'spawned':1: "
                       "sensor 'bad' on link 'l': <update_rate> value '-2' must be finite and >= 0");
  const auto* side = dynamic_cast<const SimLidar*>(sim.findSensor(id, "side"));
  ASSERT_NE(side, nullptr);
  sim.step(100);
  ASSERT_EQ(side->ranges().size(), 3u);
  EXPECT_NEAR(side->ranges()[1], 1.0, 0.05);
  sim.removeModel("spawned");
  EXPECT_EQ(sim.sensors().size(), before);
  EXPECT_EQ(sim.findSensor(id, "side"), nullptr);
}

TEST(WorldModelSensors, AnAttachThatThrowsLeavesTheSensorOutWithTheReason) {
  std::vector<std::string> errors;
  SimulatorOptions options;
  options.log.error = [&](const std::string& e) { errors.push_back(e); };
  Simulator sim(loadWorldFile(kWorld), options);
  sim.attachWorldSensors([](SimSensor& s) {
    if (s.name() == "post_camera") throw std::runtime_error("/post_camera is taken");
  });
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "model 'sensor_post': sensor 'post_camera' left out: /post_camera is taken");
  const ModelId post = sim.findModel("sensor_post");
  EXPECT_EQ(sim.findSensor(post, "post_camera"), nullptr);
  ASSERT_EQ(sim.leftOut(post).count("post_camera"), 1u);
  EXPECT_EQ(sim.leftOut(post).at("post_camera"), "/post_camera is taken");
  EXPECT_NE(sim.findSensor(post, "post_lidar"), nullptr);
  sim.step(10);
}

}  // namespace
}  // namespace tianracer_sim
