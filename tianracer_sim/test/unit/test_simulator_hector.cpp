// hector_gazebo_plugins' sensors in the simulation, on a world model (an SDF <model> with the
// three model plugins and a sonar on a ray sensor): a box falling from 2 m reads free fall on
// the IMU, the GPS altitude and vertical speed of the fall and the sonar its height; the noise
// and drift do not depend on who listens; a reset starts them again; a plugin without
// <bodyName> on a world model is left out with its place.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/hector/sim_hector.h"
#include "tianracer_sim/simulator/simulator.h"
#include "tianracer_sim/world/world.h"

namespace tianracer_sim {
namespace {

const char* kWorld = R"(<sdf version="1.6"><world name="hector">
<model name="ground"><static>true</static><link name="l"><collision name="c"><geometry>
  <plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision></link></model>
<model name="faller">
  <pose>0 0 2 0 0 0</pose>
  <link name="body">
    <inertial><mass>1</mass><inertia><ixx>0.01</ixx><iyy>0.01</iyy><izz>0.01</izz></inertia></inertial>
    <collision name="c"><geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision>
    <sensor type="ray" name="down">
      <pose>0 0 0 0 1.5707963267948966 0</pose>
      <update_rate>20</update_rate>
      <ray><scan><horizontal><samples>1</samples><min_angle>0</min_angle><max_angle>0</max_angle></horizontal></scan>
        <range><min>0.11</min><max>5</max></range></ray>
      <plugin name="sonar" filename="libhector_gazebo_ros_sonar.so"><updateRate>100</updateRate></plugin>
    </sensor>
  </link>
  <plugin name="imu" filename="libhector_gazebo_ros_imu.so">
    <bodyName>body</bodyName><updateRate>100</updateRate>
    <accelGaussianNoise>0.1 0.1 0.1</accelGaussianNoise><rateDrift>0.1 0.1 0.1</rateDrift>
  </plugin>
  <plugin name="gps" filename="libhector_gazebo_ros_gps.so">
    <bodyName>body</bodyName><updateRate>100</updateRate><referenceAltitude>100</referenceAltitude>
  </plugin>
  <plugin name="compass" filename="libhector_gazebo_ros_magnetic.so"><bodyName>body</bodyName></plugin>
</model>
<model name="post"><static>true</static><pose>5 0 0 0 0 0</pose>
  <link name="l"><collision name="c"><geometry><box><size>0.1 0.1 1</size></box></geometry></collision></link>
  <plugin name="nobody" filename="libhector_gazebo_ros_gps.so"/>
</model>
</world></sdf>)";

/// Wants the outputs while *on.
class Switch : public SensorListener {
 public:
  explicit Switch(const bool* on) : on_(on) {}
  SensorOutputs wanted(const SimSensor&, SensorOutputs due) override { return *on_ ? due : 0; }
  void onOutputs(const SimSensor&, SensorOutputs, double) override {}

 private:
  const bool* on_;
};

WorldDescription world() { return loadWorldString(kWorld, "hector.world", "."); }

TEST(SimulatorHector, AFallingWorldModelsImuGpsCompassAndSonar) {
  std::vector<std::string> errors;
  SimulatorOptions options;
  options.log.error = [&](const std::string& e) { errors.push_back(e); };
  Simulator sim(world(), options);
  const ModelId faller = sim.findModel("faller");
  ASSERT_NE(faller, kNoModel);
  const auto* imu = dynamic_cast<const SimHectorImu*>(sim.findSensor(faller, "imu"));
  const auto* gps = dynamic_cast<const SimHectorGps*>(sim.findSensor(faller, "gps"));
  const auto* compass = dynamic_cast<const SimHectorMagnetic*>(sim.findSensor(faller, "compass"));
  const auto* sonar = dynamic_cast<const SimHectorSonar*>(sim.findSensor(faller, "down"));
  ASSERT_TRUE(imu && gps && compass && sonar);
  EXPECT_EQ(imu->frame(), "body");
  EXPECT_EQ(gps->frame(), "world");
  // The post's GPS has no <bodyName>: a world model's canonical link is not known here.
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("hector.world:"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("hector GPS plugin 'nobody' of model 'post': no <bodyName>"),
            std::string::npos)
      << errors[0];

  sim.step(300);  // 0.3 s of free fall
  const double t = 0.3, z = 2.0 - 0.5 * 9.8 * t * t;
  EXPECT_NEAR(imu->reading().imu.linear_acceleration.norm(), 0.0, 0.5);  // free fall, noise 0.1
  EXPECT_NEAR(gps->reading().altitude, 100.0 + z, 0.01);
  EXPECT_NEAR(gps->reading().velocity.z(), -9.8 * t, 0.02);
  EXPECT_NEAR(gps->reading().latitude, 49.9, 1e-9);
  EXPECT_NEAR(sonar->reading().range, z, 0.01);  // the ground (its own box is within range min)
  EXPECT_NEAR((compass->field() - Eigen::Vector3d(0.5, 0, -std::sqrt(0.75))).norm(), 0, 1e-6);
  sim.step(1700);  // landed: resting on its face, 0.1 m up
  double az = 0;
  for (int k = 0; k < 100; ++k) {
    sim.step(10);
    az += imu->reading().imu.linear_acceleration.z();
  }
  EXPECT_NEAR(az / 100, 9.8, 0.05);
  // Its rays start at range min, 1 cm under the ground: nothing ahead within range, range max.
  EXPECT_FLOAT_EQ(sonar->reading().range, 5.0f);
  EXPECT_NEAR(gps->reading().altitude, 100.1, 0.01);
}

TEST(SimulatorHector, NoiseDoesNotDependOnWhoListensAndAResetStartsAgain) {
  bool heard = true, unheard = false;
  SimulatorOptions a_options, b_options;
  a_options.seed = b_options.seed = 17;
  Simulator a(world(), a_options), b(world(), b_options);
  a.attachWorldSensors([&](SimSensor& s) { s.setListener(std::make_unique<Switch>(&heard)); });
  b.attachWorldSensors([&](SimSensor& s) { s.setListener(std::make_unique<Switch>(&unheard)); });
  a.step(200);
  b.step(200);  // nobody listens to b's sensors: skip() runs their models all the same
  unheard = true;
  a.step(1);
  b.step(1);
  const auto imu = [](const Simulator& s) {
    return dynamic_cast<const SimHectorImu*>(s.findSensor(s.findModel("faller"), "imu"));
  };
  EXPECT_EQ(imu(a)->reading().imu.linear_acceleration, imu(b)->reading().imu.linear_acceleration);
  EXPECT_EQ(imu(a)->reading().bias.angular_velocity, imu(b)->reading().bias.angular_velocity);
  // Another seed, other noise.
  SimulatorOptions c_options;
  c_options.seed = 18;
  Simulator c(world(), c_options);
  c.step(201);
  EXPECT_NE(imu(a)->reading().imu.linear_acceleration, imu(c)->reading().imu.linear_acceleration);
  // reset_simulation: the box back at 2 m, the GPS there at the first update.
  a.step(500);
  a.resetSimulation();
  a.step(1);
  const auto* gps = dynamic_cast<const SimHectorGps*>(a.findSensor(a.findModel("faller"), "gps"));
  EXPECT_NEAR(gps->reading().altitude, 102.0, 0.01);
  EXPECT_TRUE(imu(a)->reading().imu.linear_acceleration.allFinite());
}

}  // namespace
}  // namespace tianracer_sim
