// The IMU: readings at rest and in known motion against analytic values, noise and bias
// statistics, configuration from SDF and both gazebo_ros plugins, and bad input.
#include <cmath>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tianracer_sim/plugins/imu/imu_sensor.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using ::testing::HasSubstr;

const Eigen::Vector3d kGravity(0.0, 0.0, -9.81);
constexpr double kDt = 0.001;

/// One link with the given <gazebo> body, parsed as the model loader does.
RobotExtensions extFrom(const std::string& gazebo) {
  return parseExtensions("<robot name='r'><link name='base'/>" + gazebo + "</robot>", "test.urdf",
                         {});
}
SensorSpec imuSpec(const std::string& inner, const std::string& plugin =
                       "<plugin name='p' filename='libgazebo_ros_imu_sensor.so'>"
                       "<topicName>imu</topicName><frameName>imu_link</frameName>"
                       "<updateRateHZ>100</updateRateHZ></plugin>") {
  const RobotExtensions ext = extFrom("<gazebo reference='base'><sensor type='imu' name='imu_sensor'>"
                                      "<update_rate>100</update_rate>" + inner + plugin +
                                      "</sensor></gazebo>");
  return ext.links.at("base").sensors.at(0);
}

// Mean and standard deviation of the samples added.
struct SampleStats {
  double sum = 0, sum2 = 0;
  int n = 0;
  void add(double x) {
    sum += x;
    sum2 += x * x;
    ++n;
  }
  double mean() const { return sum / n; }
  double sd() const { return std::sqrt(sum2 / n - mean() * mean()); }
};

constexpr int kSamples = 10000;

// Over kSamples readings at rest, one every kDt, `reading` has mean `mean` (within mean_tol)
// and standard deviation `sd` (within sd_tol).
template <class F>
void expectRestingNoise(ImuSensor& imu, F reading, double mean, double mean_tol, double sd,
                        double sd_tol) {
  SampleStats stats;
  for (int k = 0; k < kSamples; ++k) {
    imu.record(k * kDt, Eigen::Isometry3d::Identity());
    stats.add(reading(imu.read()));
  }
  EXPECT_NEAR(stats.mean(), mean, mean_tol);
  EXPECT_NEAR(stats.sd(), sd, sd_tol);
}

ImuConfig quiet() {
  ImuConfig c;
  c.name = "imu";
  c.link = "base";
  c.has_plugin = true;
  c.topic_name = "imu";
  c.frame_name = "imu_link";
  return c;
}

Eigen::Isometry3d rotZ(double a, const Eigen::Vector3d& p = Eigen::Vector3d::Zero()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p;
  return X;
}

TEST(SensorsImu, AtRestReadsSpecificForceUp) {
  ImuSensor imu(quiet(), kGravity);
  for (int k = 0; k < 20; ++k) imu.record(k * kDt, rotZ(0.3, Eigen::Vector3d(1, 2, 0.1)));
  imu.skip();
  for (int k = 20; k < 30; ++k) imu.record(k * kDt, rotZ(0.3, Eigen::Vector3d(1, 2, 0.1)));
  const ImuReading& r = imu.read();
  EXPECT_NEAR(r.linear_acceleration.x(), 0.0, 1e-9);
  EXPECT_NEAR(r.linear_acceleration.y(), 0.0, 1e-9);
  EXPECT_NEAR(r.linear_acceleration.z(), 9.81, 0.01);
  EXPECT_NEAR(r.angular_velocity.norm(), 0.0, 1e-9);
  // Orientation in the world frame: yaw 0.3.
  const Eigen::Quaterniond q(r.orientation_xyzw[3], r.orientation_xyzw[0], r.orientation_xyzw[1],
                             r.orientation_xyzw[2]);
  EXPECT_NEAR(q.angularDistance(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()))),
              0.0, 1e-9);
  for (double c : r.linear_acceleration_covariance) EXPECT_EQ(c, 0.0);
}

TEST(SensorsImu, TiltedSensorSeesGravityInItsFrame) {
  ImuConfig c = quiet();
  c.X_LS.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  ImuSensor imu(c, kGravity);
  for (int k = 0; k < 5; ++k) imu.record(k * kDt, Eigen::Isometry3d::Identity());
  const ImuReading& r = imu.read();
  // Sensor z is world -y, sensor y is world z: up is +y in the sensor.
  EXPECT_NEAR(r.linear_acceleration.y(), 9.81, 1e-9);
  EXPECT_NEAR(r.linear_acceleration.z(), 0.0, 1e-9);
}

TEST(SensorsImu, SpunBodyReadsItsRateAndCentripetalAcceleration) {
  // A link spinning at w about world z; the sensor 0.2 m off the axis along the link's x.
  for (const double w : {0.5, 2.0, -7.0}) {
    ImuConfig c = quiet();
    c.X_LS.translation() = Eigen::Vector3d(0.2, 0.0, 0.0);
    ImuSensor imu(c, kGravity);
    int reads = 0;
    for (int k = 0; k <= 2000; ++k) {
      imu.record(k * kDt, rotZ(w * k * kDt));
      if (k % 10 != 0) continue;  // 100 Hz samples
      const ImuReading& r = imu.read();
      if (k < 20) continue;  // the first sample has no interval behind it
      ++reads;
      EXPECT_NEAR(r.angular_velocity.z(), w, 1e-3 * std::abs(w));
      EXPECT_NEAR(r.angular_velocity.x(), 0.0, 1e-9);
      // Centripetal: -w^2 r along the sensor's x (towards the axis).
      EXPECT_NEAR(r.linear_acceleration.x(), -w * w * 0.2, 1e-3 * w * w * 0.2);
      EXPECT_NEAR(r.linear_acceleration.z(), 9.81, 1e-9);
      const double yaw = 2.0 * std::atan2(r.orientation_xyzw[2], r.orientation_xyzw[3]);
      EXPECT_NEAR(std::remainder(yaw - w * k * kDt, 2 * M_PI), 0.0, 1e-9);
    }
    EXPECT_GT(reads, 100);
  }
}

TEST(SensorsImu, LinearAccelerationIsTheMeanOverTheSampleInterval) {
  // x(t) = 0.5 a t^2 along world x: a constant acceleration reads a, plus gravity's reaction.
  ImuSensor imu(quiet(), kGravity);
  const double a = 1.5;
  for (int k = 0; k <= 100; ++k) {
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation().x() = 0.5 * a * std::pow(k * kDt, 2);
    imu.record(k * kDt, X);
    if (k % 20 == 0 && k > 0) {
      const ImuReading& r = imu.read();
      if (k > 20) {
        EXPECT_NEAR(r.linear_acceleration.x(), a, 1e-6);
      }
    }
  }
}

TEST(SensorsImu, NoiseAndBiasStatistics) {
  ImuConfig c = quiet();
  ImuAxisNoise n;
  n.type = "gaussian";
  n.mean = 0.05;
  n.stddev = 0.02;
  c.rate_noise.fill(n);
  ImuSensor imu(c, kGravity);
  expectRestingNoise(imu, [](const ImuReading& r) { return r.angular_velocity.x(); }, 0.05, 0.005,
                     0.02, 0.002);
  EXPECT_DOUBLE_EQ(imu.read().angular_velocity_covariance[0], 0.02 * 0.02);

  // Bias: drawn once per sensor, N(bias_mean, bias_stddev) with a random sign.
  ImuAxisNoise b;
  b.type = "gaussian";
  b.bias_mean = 0.1;
  b.bias_stddev = 0.01;
  SampleStats bias_size;
  int negative = 0;
  for (int s = 0; s < kSamples; ++s) {
    ImuConfig cb = quiet();
    cb.accel_noise.fill(b);
    cb.seed = s;
    ImuSensor biased(cb, kGravity);
    const double bias = biased.biases()[3];
    negative += bias < 0;
    bias_size.add(std::abs(bias));
  }
  EXPECT_NEAR(bias_size.mean(), 0.1, 0.01);
  EXPECT_NEAR(bias_size.sd(), 0.01, 0.001);
  EXPECT_NEAR(negative / double(kSamples), 0.5, 0.05);

  // The bias is in every sample: at rest the mean reading is 9.81 + bias.
  ImuConfig cb = quiet();
  cb.accel_noise.fill(b);
  cb.seed = 7;
  ImuSensor biased(cb, kGravity);
  biased.record(0.0, Eigen::Isometry3d::Identity());
  biased.record(kDt, Eigen::Isometry3d::Identity());
  EXPECT_NEAR(biased.read().linear_acceleration.z(), 9.81 + biased.biases()[5], 1e-9);
}

TEST(SensorsImu, PluginGaussianNoise) {
  ImuConfig c = quiet();
  c.gaussian_noise = 0.03;
  ImuSensor imu(c, kGravity);
  expectRestingNoise(imu, [](const ImuReading& r) { return r.linear_acceleration.x(); }, 0.0, 0.003,
                     0.03, 0.003);
  EXPECT_DOUBLE_EQ(imu.read().orientation_covariance[4], 0.03 * 0.03);
}

TEST(SensorsImu, SensorAndPluginConfig) {
  const SensorSpec spec = imuSpec(
      "<pose>0 0 0.1 0 0 0</pose><imu><angular_velocity>"
      "<x><noise type='gaussian'><mean>0</mean><stddev>0.0002</stddev><bias_mean>7.5e-06</bias_mean>"
      "<bias_stddev>8e-07</bias_stddev></noise></x>"
      "<z><noise type='gaussian_quantized'><stddev>0.1</stddev><precision>0.01</precision></noise></z>"
      "</angular_velocity><linear_acceleration><y><noise type='none'/></y></linear_acceleration></imu>");
  const ImuConfig c = parseImuSensorConfig(spec, "car");
  EXPECT_EQ(c.rate_noise[0].type, "gaussian");
  EXPECT_DOUBLE_EQ(c.rate_noise[0].stddev, 0.0002);
  EXPECT_DOUBLE_EQ(c.rate_noise[0].bias_mean, 7.5e-06);
  EXPECT_EQ(c.rate_noise[2].type, "gaussian_quantized");
  EXPECT_EQ(c.accel_noise[1].type, "none");
  EXPECT_EQ(c.topic(), "/car/imu");  // no robotNamespace: the model's name
  EXPECT_EQ(c.frame_name, "imu_link");
  EXPECT_DOUBLE_EQ(c.publishRate(), 100.0);
  EXPECT_FALSE(c.initial_orientation_as_reference);  // REP 145: the world is the reference
  EXPECT_EQ(test::kindOf(spec), "imu");
  const std::vector<SensorTopic> t = sensorTopics(spec, "car");
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].msg_type, "sensor_msgs/Imu");

  // Plugin defaults: updateRateHZ 1 (Gazebo's), the slower of sensor and plugin.
  const ImuConfig d = parseImuSensorConfig(
      imuSpec("", "<plugin name='p' filename='libgazebo_ros_imu_sensor.so'>"
                  "<robotNamespace>/ns</robotNamespace><frameName>f</frameName>"
                  "<initialOrientationAsReference>true</initialOrientationAsReference></plugin>"),
      "car");
  EXPECT_EQ(d.topic(), "/ns/imu_data");
  EXPECT_DOUBLE_EQ(d.publishRate(), 1.0);
  EXPECT_TRUE(d.initial_orientation_as_reference);

  // The model plugin, libgazebo_ros_imu.
  const RobotExtensions ext = extFrom(
      "<gazebo><plugin name='imu_plugin' filename='libgazebo_ros_imu.so'><bodyName>base</bodyName>"
      "<topicName>imu/data</topicName><updateRate>50</updateRate><gaussianNoise>0.01</gaussianNoise>"
      "<rpyOffset>0 0 0.5</rpyOffset></plugin></gazebo>");
  const SensorSpec plugin = modelPluginSensor(ext.model_plugins.at(0));
  EXPECT_EQ(test::kindOf(plugin), "imu_plugin");
  const ImuConfig m = parseImuPluginConfig(plugin, "car");
  EXPECT_EQ(m.link, "base");
  EXPECT_EQ(m.frame_name, "base");  // frameName defaults to bodyName
  EXPECT_EQ(m.topic(), "/imu/data");
  EXPECT_EQ(m.service_name, "/default_imu");
  EXPECT_DOUBLE_EQ(m.publishRate(), 50.0);
  // rpyOffset turns the reported orientation.
  ImuConfig mq = m;
  mq.gaussian_noise = 0.0;
  ImuSensor imu(mq, kGravity);
  imu.record(0.0, Eigen::Isometry3d::Identity());
  const Eigen::Vector4d q = imu.read().orientation_xyzw;
  EXPECT_NEAR(2.0 * std::atan2(q[2], q[3]), 0.5, 1e-12);
}

TEST(SensorsImu, InitialOrientationAsReference) {
  ImuConfig c = quiet();
  c.initial_orientation_as_reference = true;
  ImuSensor imu(c, kGravity);
  imu.record(0.0, rotZ(1.0));
  imu.record(kDt, rotZ(1.25));
  const Eigen::Vector4d q = imu.read().orientation_xyzw;
  EXPECT_NEAR(2.0 * std::atan2(q[2], q[3]), 0.25, 1e-12);
}

void expectError(const std::function<void()>& f, const std::vector<std::string>& needles) {
  try {
    f();
    ADD_FAILURE() << "expected SensorError";
  } catch (const SensorError& e) {
    for (const std::string& n : needles) EXPECT_THAT(e.what(), HasSubstr(n));
  }
}

TEST(SensorsImu, BadInput) {
  // An unknown noise type names the model, the sensor, the element and the value.
  expectError([] {
    parseImuSensorConfig(imuSpec("<imu><linear_acceleration><x><noise type='laplace'>"
                                 "</noise></x></linear_acceleration></imu>"),
                         "car");
  }, {"IMU sensor 'imu_sensor'", "model 'car'", "<linear_acceleration><x><noise>", "'laplace'",
       // placed at the <sensor>'s line of its model file, then the sensor
       "test.urdf:1: IMU sensor 'imu_sensor' on link 'base' of model 'car': "});
  expectError([] {
    parseImuSensorConfig(imuSpec("<imu><noise><type>pink</type><rate><stddev>1</stddev></rate>"
                                 "</noise></imu>"),
                         "car");
  }, {"imu_sensor", "'pink'"});
  // Negative and NaN rates: the model loader sets the sensor's error (the robot loads)...
  for (const std::string rate : {"-5", "nan"}) {
    const RobotExtensions ext = extFrom("<gazebo reference='base'><sensor type='imu' name='imu_sensor'>"
                                        "<update_rate>" + rate + "</update_rate></sensor></gazebo>");
    const SensorSpec& spec = ext.links.at("base").sensors.at(0);
    EXPECT_THAT(spec.error, HasSubstr("imu_sensor"));
    EXPECT_THAT(spec.error, HasSubstr("'" + rate + "'"));
  }
  // ... the rate is read once there; a spec made without the loader is still checked.
  SensorSpec nan_rate = imuSpec("");
  nan_rate.update_rate = std::nan("");
  expectError([&] { parseImuSensorConfig(nan_rate, "car"); }, {"imu_sensor", "<update_rate>", "nan"});
  expectError([] {
    parseImuSensorConfig(imuSpec("", "<plugin name='p' filename='libgazebo_ros_imu_sensor.so'>"
                                     "<frameName>f</frameName><updateRateHZ>-1</updateRateHZ></plugin>"),
                         "car");
  }, {"imu_sensor", "<updateRateHZ> -1"});
  // The model plugin needs its body.
  const RobotExtensions ext = extFrom(
      "<gazebo><plugin name='imu_plugin' filename='libgazebo_ros_imu.so'><topicName>imu</topicName>"
      "</plugin></gazebo>");
  expectError([&] { parseImuPluginConfig(modelPluginSensor(ext.model_plugins.at(0)), "car"); },
              {"IMU plugin 'imu_plugin'", "model 'car'", "<bodyName> is missing"});
}

}  // namespace
}  // namespace tianracer_sim
