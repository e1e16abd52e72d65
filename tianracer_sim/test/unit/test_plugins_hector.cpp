// hector_gazebo_plugins' IMU, GPS, magnetometer and sonar (plugins/hector/): parameters as
// upstream (melodic-devel) reads them with their defaults, bad values with file:line messages,
// sensor_model.h's noise and drift statistics with a fixed seed, update_timer.h's schedule,
// the GPS conversion against numbers computed by hand from gazebo_ros_gps.cpp's formulas, the
// IMU's and magnetometer's readings at known poses, and the sonar's minimum range against a
// wall at a known distance.
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/plugins/hector/hector_gps.h"
#include "tianracer_sim/plugins/hector/hector_imu.h"
#include "tianracer_sim/plugins/hector/hector_magnetic.h"
#include "tianracer_sim/plugins/hector/hector_model.h"
#include "tianracer_sim/plugins/hector/hector_sonar.h"
#include "tianracer_sim/plugins/sensor_registry.h"

#include "common_test_support.h"
#include "sensor_test_support.h"

namespace tianracer_sim {
namespace {

using Params = std::map<std::string, std::string>;

// A model plugin as the model loader gives it, seen as a sensor (modelPluginSensor()).
SensorSpec plugin(const std::string& filename, Params params, const std::string& name = "p") {
  PluginSpec p;
  p.name = name;
  p.filename = filename;
  p.params = std::move(params);
  p.source = "bot.urdf";
  p.line = 12;
  return modelPluginSensor(p);
}

template <typename F>
std::string errorOf(F f) {
  return test::errorText<SensorError>([&] { f(); }, "(no error)");
}

std::vector<std::string> warningsOf(const std::function<void(const WarningSink&)>& f) {
  std::vector<std::string> w;
  f([&](const std::string& s) { w.push_back(s); });
  return w;
}

LinkState at(const Eigen::Vector3d& p, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity(),
             const Eigen::Vector3d& v = Eigen::Vector3d::Zero()) {
  LinkState s;
  s.X_WL.translation() = p;
  s.X_WL.linear() = q.toRotationMatrix();
  s.v_W = v;
  return s;
}

const Eigen::Vector3d kGravity(0, 0, -9.8);

// ---- sensor_model.h and update_timer.h ------------------------------------------------------

TEST(HectorErrorModel, DriftIsUpstreamsGaussMarkovWithItsStationaryVariance) {
  // drift = exp(-f dt) drift + dt N(0, sqrt(2 f) drift): stationary variance
  // 2 f dt^2 drift^2 / (1 - exp(-2 f dt)) (not drift^2: upstream scales the noise by dt).
  HectorErrorModel1 m;
  m.drift[0] = 0.5;
  m.drift_frequency[0] = 5.0;
  m.gaussian_noise[0] = 0.02;
  m.offset[0] = 0.3;
  std::mt19937_64 rng(7);
  m.reset(rng);
  const double dt = 0.01;
  for (int i = 0; i < 2000; ++i) m.update(dt, rng);  // forget the start (100 time constants)
  const int n = 1000000;
  double s_d = 0, s_dd = 0, s_lag = 0, s_n = 0, s_nn = 0, s_e = 0;
  double last = m.current_drift[0];
  for (int i = 0; i < n; ++i) {
    const double e = m.update(dt, rng)[0];
    const double d = m.current_drift[0];
    const double noise = e - m.offset[0] - d;
    s_d += d;
    s_dd += d * d;
    s_lag += d * last;
    s_n += noise;
    s_nn += noise * noise;
    s_e += e;
    last = d;
  }
  const double var = 2 * 5.0 * dt * dt * 0.25 / (1 - std::exp(-2 * 5.0 * dt));
  EXPECT_NEAR(s_d / n, 0.0, 0.002);
  EXPECT_NEAR(s_dd / n, var, 0.03 * var);
  EXPECT_NEAR(s_lag / s_dd, std::exp(-5.0 * dt), 0.002);  // lag-1 autocorrelation
  EXPECT_NEAR(s_n / n, 0.0, 1e-4);
  EXPECT_NEAR(std::sqrt(s_nn / n), 0.02, 2e-4);
  EXPECT_NEAR(s_e / n, 0.3, 0.002);  // the offset
  // The same seed, the same sequence.
  HectorErrorModel1 a = m, b = m;
  std::mt19937_64 ra(3), rb(3);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a.update(dt, ra)[0], b.update(dt, rb)[0]);
}

TEST(HectorErrorModel, ResetDrawsTheDriftScaleAndBias) {
  HectorErrorModel3 m;
  m.drift = Eigen::Vector3d(0.1, 0.2, 0.0);
  std::mt19937_64 rng(11);
  double s1 = 0, s2 = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    m.reset(rng);
    s1 += m.current_drift.x() * m.current_drift.x();
    s2 += m.current_drift.y() * m.current_drift.y();
    EXPECT_EQ(m.current_drift.z(), 0.0);
  }
  EXPECT_NEAR(std::sqrt(s1 / n), 0.1, 0.001);  // reset(): N(0, drift)
  EXPECT_NEAR(std::sqrt(s2 / n), 0.2, 0.002);
  // operator()(value, dt) = value * scale + error; with dt 0 the drift stays; bias = drift + offset.
  m.drift.setZero();
  m.offset = Eigen::Vector3d(1, 2, 3);
  m.scale_error = Eigen::Vector3d(2, 1, 0.5);
  m.reset(Eigen::Vector3d(0.5, 0, 0));  // calibrate / set_*_bias
  EXPECT_EQ(m.current_error, Eigen::Vector3d::Zero());
  const Eigen::Vector3d out = m.apply(Eigen::Vector3d(1, 1, 1), 0.0, rng);
  EXPECT_EQ(out, Eigen::Vector3d(2 + 1.5, 1 + 2, 0.5 + 3));
  EXPECT_EQ(m.bias(), Eigen::Vector3d(1.5, 2, 3));
  // Defaults: time constant one hour, scale 1, the rest 0.
  const HectorErrorModel3 d;
  EXPECT_DOUBLE_EQ(d.drift_frequency.x(), 1.0 / 3600.0);
  EXPECT_EQ(d.scale_error, Eigen::Vector3d::Ones());
}

TEST(HectorClock, UpdateTimersGridAndDt) {
  HectorClock every;  // period 0: every step, dt 0 at the first
  EXPECT_TRUE(every.due(0.001));
  EXPECT_DOUBLE_EQ(every.tick(0.001), 0.0);
  EXPECT_TRUE(every.due(0.002));
  EXPECT_NEAR(every.tick(0.002), 0.001, 1e-12);
  HectorClock gps(HectorUpdateTimer{0.25, 0.1});  // 4 Hz from 0.1 s
  std::vector<double> fired;
  for (int k = 1; k <= 1000; ++k) {
    const double t = k * 0.001;
    if (gps.due(t)) fired.push_back(t);
  }
  ASSERT_EQ(fired.size(), 4u);
  EXPECT_NEAR(fired[0], 0.1, 1e-9);
  EXPECT_NEAR(fired[3], 0.85, 1e-9);
  gps.restart(0.0);  // reset_simulation: dt 0 again, and nothing before the offset
  EXPECT_FALSE(gps.due(0.05));
  EXPECT_TRUE(gps.due(0.1));
  EXPECT_DOUBLE_EQ(gps.tick(0.1), 0.0);
}

// ---- libhector_gazebo_ros_imu ---------------------------------------------------------------

TEST(HectorImuConfig, DefaultsAsGazeboRosImu) {
  const SensorSpec spec = plugin("libhector_gazebo_ros_imu.so", {});
  EXPECT_EQ(test::kindOf(spec), "hector_imu");
  const HectorImuConfig c = parseHectorImuConfig(spec, "bot");
  EXPECT_EQ(c.link, "");      // the canonical link, resolved by the simulation
  EXPECT_EQ(c.frame_id, "");  // the link's name
  EXPECT_EQ(c.topic(), "/imu");  // no model-name namespace, unlike gazebo_plugins
  EXPECT_EQ(c.biasTopic(), "/imu/bias");
  EXPECT_EQ(c.service(), "/imu/calibrate");
  EXPECT_EQ(c.timer.period, 0.0);  // every step
  EXPECT_EQ(c.accel.gaussian_noise, Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(c.yaw.drift_frequency[0], 1.0 / 3600.0);
  EXPECT_EQ(test::topicNames(publishedTopics(c)),
            (std::vector<std::string>{"/imu", "/imu/bias"}));
}

TEST(HectorImuConfig, EveryParameterUpstreamReads) {
  const std::vector<std::string> w = warningsOf([](const WarningSink& warn) {
    const HectorImuConfig c = parseHectorImuConfig(
        plugin("libhector_gazebo_ros_imu.so",
               {{"robotNamespace", "/"}, {"updateRate", "50.0"}, {"bodyName", "base_link"},
                {"frameId", "/imu_link"}, {"topicName", "imu/data"}, {"biasTopicName", "imu/b"},
                {"serviceName", "imu/cal"}, {"accelOffset", "0.1 0.2 0.3"},
                {"accelDrift", "0.005 0.005 0.005"}, {"accelDriftFrequency", "0.1 0.1 0.1"},
                {"accelGaussianNoise", "0.005 0.005 0.006"}, {"accelScaleError", "1 1 1.01"},
                {"rateDrift", "0.005 0.005 0.005 "}, {"rateGaussianNoise", "0.005 0.005 0.005"},
                {"yawOffset", "0.01"}, {"yawDrift", "0.02"}, {"yawGaussianNoise", "0.03"},
                {"xyzOffset", "0 0 0.1"}, {"rpyOffset", "0 0 1.5707963"},
                {"headingDrift", "0.005"}, {"alwaysOn", "true"}}),
        "jackal", warn);
    EXPECT_EQ(c.link, "base_link");
    EXPECT_EQ(c.frame_id, "imu_link");
    EXPECT_EQ(c.topic(), "/imu/data");
    EXPECT_EQ(c.biasTopic(), "/imu/b");
    EXPECT_EQ(c.service(), "/imu/cal");
    EXPECT_DOUBLE_EQ(c.timer.rate(), 50.0);
    EXPECT_EQ(c.accel.offset, Eigen::Vector3d(0.1, 0.2, 0.3));
    EXPECT_EQ(c.accel.gaussian_noise, Eigen::Vector3d(0.005, 0.005, 0.006));
    EXPECT_EQ(c.accel.scale_error, Eigen::Vector3d(1, 1, 1.01));
    EXPECT_EQ(c.rate.drift, Eigen::Vector3d::Constant(0.005));
    EXPECT_DOUBLE_EQ(c.yaw.offset[0], 0.01);
    EXPECT_DOUBLE_EQ(c.yaw.gaussian_noise[0], 0.03);
    EXPECT_DOUBLE_EQ(c.rpy_offset.z(), 1.5707963);
  });
  // Jackal's <headingDrift> is not hector's (yawDrift is): named, ignored.
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("bot.urdf:12: hector IMU plugin 'p' of model 'jackal': <headingDrift> is "
                      "not a parameter of libhector_gazebo_ros_imu.so, ignored"),
            std::string::npos)
      << w[0];
  // The old gazebo_ros_imu name: gaussianNoise sets both models' noise; an empty topic has no
  // bias topic; its calibrate service is "/calibrate".
  const HectorImuConfig old = parseHectorImuConfig(
      plugin("libhector_gazebo_ros_imu.so", {{"gaussianNoise", "0.2"}, {"topicName", ""}}), "b");
  EXPECT_EQ(old.accel.gaussian_noise, Eigen::Vector3d::Constant(0.2));
  EXPECT_EQ(old.rate.gaussian_noise, Eigen::Vector3d::Constant(0.2));
  EXPECT_TRUE(publishedTopics(old).empty());
  EXPECT_EQ(old.service(), "/calibrate");
}

TEST(HectorImuConfig, BadValuesNameFileLineElementAndValue) {
  const auto bad = [](Params p) {
    return errorOf([&] { parseHectorImuConfig(plugin("libhector_gazebo_ros_imu.so", p), "bot"); });
  };
  EXPECT_EQ(bad({{"accelGaussianNoise", "0.1"}}),
            "bot.urdf:12: hector IMU plugin 'p' of model 'bot': <accelGaussianNoise> '0.1' is not "
            "3 numbers");
  EXPECT_EQ(bad({{"rateDrift", "0 -1 0"}}),
            "bot.urdf:12: hector IMU plugin 'p' of model 'bot': <rateDrift> '0 -1 0' must be >= 0");
  EXPECT_EQ(bad({{"yawDriftFrequency", "fast"}}),
            "bot.urdf:12: hector IMU plugin 'p' of model 'bot': <yawDriftFrequency> 'fast' is not "
            "a number");
  EXPECT_EQ(bad({{"updateRate", "-5"}}),
            "bot.urdf:12: hector IMU plugin 'p' of model 'bot': <updateRate> -5 must be >= 0");
  EXPECT_EQ(bad({{"updatePeriod", "1 2 3"}}),
            "bot.urdf:12: hector IMU plugin 'p' of model 'bot': <updatePeriod> '1 2 3' is not a "
            "time (seconds, or sec nsec)");
  EXPECT_NE(bad({{"yawOffset", "nan"}}).find("<yawOffset> nan is not finite"), std::string::npos);
}

TEST(HectorImu, AtRestGravityUpAndNoRates) {
  HectorImuConfig c;
  HectorImu imu(c);
  const LinkState rest = at(Eigen::Vector3d(1, 2, 0.3));
  imu.update(0.0, rest, kGravity);  // the first update: dt 0, nothing differentiated yet
  EXPECT_EQ(imu.reading().imu.linear_acceleration, Eigen::Vector3d::Zero());
  const ImuReading& r = imu.update(0.01, rest, kGravity).imu;
  EXPECT_NEAR(r.linear_acceleration.z(), 9.8, 1e-12);  // the specific force, up
  EXPECT_NEAR(r.linear_acceleration.head<2>().norm(), 0.0, 1e-12);
  EXPECT_EQ(r.angular_velocity, Eigen::Vector3d::Zero());
  EXPECT_EQ(r.orientation_xyzw, Eigen::Vector4d(0, 0, 0, 1));
  EXPECT_EQ(r.orientation_covariance[0], 0.0);
  // Tilted 90 degrees about x: gravity along the body's y.
  const Eigen::Quaterniond roll(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  HectorImu tilted(c);
  tilted.update(0.0, at(Eigen::Vector3d::Zero(), roll), kGravity);
  const ImuReading& t = tilted.update(0.01, at(Eigen::Vector3d::Zero(), roll), kGravity).imu;
  EXPECT_NEAR(t.linear_acceleration.y(), 9.8, 1e-9);
  EXPECT_NEAR(t.linear_acceleration.z(), 0.0, 1e-9);
}

TEST(HectorImu, RatesAccelerationAndRpyOffset) {
  HectorImuConfig c;
  HectorImu imu(c);
  // Yawing at 0.5 rad/s and speeding up at 2 m/s^2 along x.
  const double dt = 0.01;
  for (int k = 0; k <= 3; ++k) {
    const double t = k * dt;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5 * t, Eigen::Vector3d::UnitZ()));
    imu.update(k ? dt : 0.0, at(Eigen::Vector3d::Zero(), q, Eigen::Vector3d(2 * t, 0, 0)),
               kGravity);
  }
  const ImuReading& r = imu.reading().imu;
  EXPECT_NEAR(r.angular_velocity.z(), 0.5, 1e-9);
  const double yaw = 0.5 * 3 * dt;  // a = 2 along world x, seen in the body
  EXPECT_NEAR(r.linear_acceleration.x(), 2 * std::cos(yaw), 1e-9);
  EXPECT_NEAR(r.linear_acceleration.y(), -2 * std::sin(yaw), 1e-9);
  // rpyOffset: rot = q_o * q, the rate turned back by q_o^-1 (upstream's sides).
  c.rpy_offset = Eigen::Vector3d(M_PI / 2, 0, 0);
  HectorImu off(c);
  const Eigen::Quaterniond qo(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  for (int k = 0; k <= 1; ++k) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.5 * k * dt, Eigen::Vector3d::UnitZ()));
    off.update(k ? dt : 0.0, at(Eigen::Vector3d::Zero(), q), kGravity);
  }
  const Eigen::Quaterniond q1(Eigen::AngleAxisd(0.5 * dt, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond rot = qo * q1;
  const Eigen::Vector4d& o = off.reading().imu.orientation_xyzw;
  EXPECT_NEAR(o[0], rot.x(), 1e-12);
  EXPECT_NEAR(o[3], rot.w(), 1e-12);
  // delta = (q_o q0)^-1 (q_o q1) = q0^-1 q1: a yaw of 0.5 dt, then turned by q_o^-1.
  const Eigen::Vector3d expected = qo.conjugate() * Eigen::Vector3d(0, 0, 0.5);
  EXPECT_NEAR((off.reading().imu.angular_velocity - expected).norm(), 0.0, 1e-9);
  // specific force rot^-1 (-g): with the offset's roll of 90 degrees, along -y... as upstream.
  EXPECT_NEAR((off.reading().imu.linear_acceleration - rot.conjugate() * Eigen::Vector3d(0, 0, 9.8)).norm(),
              0.0, 1e-9);
}

TEST(HectorImu, OrientationErrorBiasMessageCovariancesAndCalibrate) {
  HectorImuConfig c;
  c.accel.offset = Eigen::Vector3d(0.098, 0, 0);  // tilts the orientation by about 0.01 rad
  c.yaw.offset[0] = 0.2;
  c.rate.offset = Eigen::Vector3d(0, 0, 0.01);
  c.rate.drift = Eigen::Vector3d(0, 0, 0.05);
  c.accel.gaussian_noise = Eigen::Vector3d(0.098, 0.196, 0.3);
  c.rate.gaussian_noise = Eigen::Vector3d(0.1, 0.2, 0.3);
  c.yaw.gaussian_noise[0] = 0.5;
  c.seed = 5;
  HectorImu imu(c);
  const HectorImuReading& r = imu.update(0.0, at(Eigen::Vector3d::Zero()), kGravity);
  // e = yaw(0.2) * (1, d.y / 2g, -d.x / 2g, 0), d the accel bias in the world.
  const Eigen::Quaterniond e =
      (Eigen::Quaterniond(std::cos(0.1), 0, 0, std::sin(0.1)) *
       Eigen::Quaterniond(1.0, 0.0, -0.5 * 0.098 / 9.8, 0.0)).normalized();
  EXPECT_NEAR((r.bias.orientation_xyzw - Eigen::Vector4d(e.x(), e.y(), e.z(), e.w())).norm(), 0,
              1e-12);
  EXPECT_NEAR((r.imu.orientation_xyzw - r.bias.orientation_xyzw).norm(), 0, 1e-12);  // e * identity
  EXPECT_EQ(r.bias.linear_acceleration, Eigen::Vector3d(0.098, 0, 0));
  const double rate_bias = r.bias.angular_velocity.z();
  EXPECT_NE(rate_bias, 0.01);  // the drift drawn at reset, N(0, 0.05), plus the offset
  EXPECT_NEAR(r.imu.orientation_covariance[0], 0.0001, 1e-15);  // (0.098 / 9.8)^2
  EXPECT_NEAR(r.imu.orientation_covariance[4], 0.0004, 1e-15);
  EXPECT_DOUBLE_EQ(r.imu.orientation_covariance[8], 0.25);
  EXPECT_DOUBLE_EQ(r.imu.angular_velocity_covariance[4], 0.04);
  EXPECT_DOUBLE_EQ(r.imu.linear_acceleration_covariance[8], 0.09);
  imu.calibrate();  // the rate drift to 0: the bias is the offset again
  EXPECT_DOUBLE_EQ(imu.update(0.0, at(Eigen::Vector3d::Zero()), kGravity).bias.angular_velocity.z(),
                   0.01);
  imu.setAccelBias(Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(imu.update(0.0, at(Eigen::Vector3d::Zero()), kGravity).bias.linear_acceleration,
            Eigen::Vector3d(0.098, 0, 1));
  // No gravity: orientation covariance -1 (upstream), no roll/pitch error.
  HectorImu space(c);
  const HectorImuReading& s = space.update(0.0, at(Eigen::Vector3d::Zero()), Eigen::Vector3d::Zero());
  EXPECT_EQ(s.imu.orientation_covariance[0], -1.0);
  EXPECT_TRUE(s.imu.orientation_xyzw.allFinite());
}

TEST(HectorImu, NoiseStatisticsWithAFixedSeed) {
  HectorImuConfig c;
  c.accel.gaussian_noise = Eigen::Vector3d::Constant(0.05);
  c.rate.gaussian_noise = Eigen::Vector3d::Constant(0.01);
  c.seed = 42;
  HectorImu imu(c), again(c);
  const int n = 100000;
  double s = 0, ss = 0, rs = 0;
  for (int k = 0; k < n; ++k) {
    const ImuReading& r = imu.update(k ? 0.01 : 0.0, at(Eigen::Vector3d::Zero()), kGravity).imu;
    if (k < 5) {  // the same seed repeats the run
      EXPECT_EQ(again.update(k ? 0.01 : 0.0, at(Eigen::Vector3d::Zero()), kGravity).imu.linear_acceleration,
                r.linear_acceleration);
    }
    if (k == 0) continue;
    const double a = r.linear_acceleration.z() - 9.8;
    s += a;
    ss += a * a;
    rs += r.angular_velocity.x() * r.angular_velocity.x();
  }
  EXPECT_NEAR(s / n, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(ss / n), 0.05, 0.0005);
  EXPECT_NEAR(std::sqrt(rs / n), 0.01, 0.0001);
}

// ---- libhector_gazebo_ros_gps ---------------------------------------------------------------

TEST(HectorGpsConfig, DefaultsParametersAndBadValues) {
  const SensorSpec spec = plugin("libhector_gazebo_ros_gps.so", {});
  EXPECT_EQ(test::kindOf(spec), "hector_gps");
  const HectorGpsConfig d = parseHectorGpsConfig(spec, "bot");
  EXPECT_EQ(d.frame_id, "world");  // upstream "/world"
  EXPECT_EQ(test::topicNames(publishedTopics(d)), (std::vector<std::string>{"/fix", "/fix_velocity"}));
  EXPECT_DOUBLE_EQ(publishedTopics(d)[0].rate, 4.0);
  EXPECT_DOUBLE_EQ(d.reference_latitude, 49.9);
  EXPECT_DOUBLE_EQ(d.reference_longitude, 8.9);
  EXPECT_EQ(d.status, 0);
  EXPECT_EQ(d.service, 0);
  // Jackal's navsat plugin.
  const HectorGpsConfig j = parseHectorGpsConfig(
      plugin("libhector_gazebo_ros_gps.so",
             {{"updateRate", "40"}, {"robotNamespace", "/"}, {"bodyName", "navsat_link"},
              {"frameId", "base_link"}, {"topicName", "/navsat/fix"},
              {"velocityTopicName", "/navsat/vel"}, {"referenceLatitude", "49.9"},
              {"referenceLongitude", "8.9"}, {"referenceHeading", "90"},
              {"referenceAltitude", "100"}, {"drift", "0.0001 0.0001 0.0001"},
              {"velocityGaussianNoise", "0.1 0.1 0.2"}, {"status", "2"}, {"service", "5"}}),
      "jackal");
  EXPECT_EQ(j.link, "navsat_link");
  EXPECT_EQ(j.frame_id, "base_link");
  EXPECT_EQ(test::topicNames(publishedTopics(j)), (std::vector<std::string>{"/navsat/fix", "/navsat/vel"}));
  EXPECT_DOUBLE_EQ(j.timer.rate(), 40.0);
  EXPECT_DOUBLE_EQ(j.reference_heading, M_PI / 2);
  EXPECT_EQ(j.position.drift, Eigen::Vector3d::Constant(0.0001));
  EXPECT_EQ(j.velocity.gaussian_noise, Eigen::Vector3d(0.1, 0.1, 0.2));
  EXPECT_EQ(j.status, 2);
  EXPECT_EQ(j.service, 5);
  const auto bad = [](Params p) {
    return errorOf([&] { parseHectorGpsConfig(plugin("libhector_gazebo_ros_gps.so", p), "bot"); });
  };
  EXPECT_EQ(bad({{"referenceLatitude", "90"}}),
            "bot.urdf:12: hector GPS plugin 'p' of model 'bot': <referenceLatitude> 90 must be "
            "within (-90, 90) degrees");
  EXPECT_NE(bad({{"status", "3"}}).find("<status> '3' must be an integer -1..2"), std::string::npos);
  EXPECT_NE(bad({{"velocityDrift", "a b c"}}).find("bot.urdf:12: hector GPS plugin 'p' of model 'bot': "
                                                   "<velocityDrift> 'a b c' is not 3 numbers"),
            std::string::npos);
  // useWorldSphericalCoordinates is named: the world's coordinates are not read here.
  const std::vector<std::string> w = warningsOf([](const WarningSink& warn) {
    parseHectorGpsConfig(plugin("libhector_gazebo_ros_gps.so", {{"useWorldSphericalCoordinates", "true"}}),
                         "bot", warn);
  });
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("<useWorldSphericalCoordinates> true"), std::string::npos) << w[0];
}

TEST(HectorGps, Wgs84RadiiAndFixAgainstHandComputedNumbers) {
  // Numbers from gazebo_ros_gps.cpp's formulas, by hand (Python, double precision).
  const GpsRadii r = gpsRadii(49.9);
  EXPECT_NEAR(r.north, 6372845.465162202, 1e-6);
  EXPECT_NEAR(r.east, 4116378.414496089, 1e-6);
  EXPECT_NEAR(gpsRadii(0.0).north, 6335439.3272928195, 1e-6);
  EXPECT_NEAR(gpsRadii(0.0).east, 6378137.0, 1e-6);
  EXPECT_NEAR(gpsRadii(-33.8688).east, 5301382.371476627, 1e-6);
  HectorGpsConfig c;
  c.reference_altitude = 10;
  HectorGpsReading f = gpsFix(c, r, Eigen::Vector3d(100, 50, 2), Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(f.latitude, 49.90089906117803, 1e-12);
  EXPECT_NEAR(f.longitude, 8.899304051113093, 1e-12);  // +y (west) lowers the longitude
  EXPECT_DOUBLE_EQ(f.altitude, 12.0);
  EXPECT_EQ(f.velocity, Eigen::Vector3d(1, 2, 3));
  c.reference_heading = M_PI / 2;
  f = gpsFix(c, r, Eigen::Vector3d(100, 50, 2), Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(f.latitude, 49.900449530589015, 1e-12);
  EXPECT_NEAR(f.longitude, 8.901391897773813, 1e-12);
  EXPECT_NEAR((f.velocity - Eigen::Vector3d(2, -1, 3)).norm(), 0, 1e-12);
  // At the origin: the reference itself; covariance drift^2 + noise^2, diagonal known.
  c.position.drift = Eigen::Vector3d(0.1, 0, 0);
  c.position.gaussian_noise = Eigen::Vector3d(0, 0.2, 0);
  f = gpsFix(c, r, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  EXPECT_DOUBLE_EQ(f.latitude, 49.9);
  EXPECT_DOUBLE_EQ(f.longitude, 8.9);
  EXPECT_NEAR(f.position_covariance[0], 0.01, 1e-15);
  EXPECT_NEAR(f.position_covariance[4], 0.04, 1e-15);
  EXPECT_EQ(f.position_covariance[8], 0.0);
}

TEST(HectorGps, VelocityDriftIntegratesIntoThePosition) {
  // A velocity drift that stays (driftFrequency 0: no decay, no drift noise): its value D is
  // drawn at reset, N(0, 1), and the velocity reads D at rest.
  HectorGpsConfig c;
  c.velocity.drift = Eigen::Vector3d(1, 0, 0);
  c.velocity.drift_frequency.setZero();
  c.position.drift_frequency.setZero();  // else the position drift decays by exp(-dt / 1 h)
  c.seed = 4;
  HectorGps gps(c);
  gps.update(0.0, at(Eigen::Vector3d::Zero()));
  const double D = gps.reading().velocity.x();
  EXPECT_NE(D, 0.0);
  for (int k = 0; k < 4; ++k) gps.update(0.25, at(Eigen::Vector3d::Zero()));
  EXPECT_DOUBLE_EQ(gps.reading().velocity.x(), D);
  // After 1 s the position has drifted 0.75 D north: upstream adds dt D after each fix, so the
  // fix lags by one update.
  const double north = (gps.reading().latitude - 49.9) * M_PI / 180 * gpsRadii(49.9).north;
  EXPECT_NEAR(north, 0.75 * D, 1e-6);
}

// ---- libhector_gazebo_ros_magnetic ----------------------------------------------------------

TEST(HectorMagnetic, DefaultsFieldAndMessageType) {
  const SensorSpec spec = plugin("libhector_gazebo_ros_magnetic.so", {});
  EXPECT_EQ(test::kindOf(spec), "hector_magnetic");
  const HectorMagneticConfig d = parseHectorMagneticConfig(spec, "bot");
  EXPECT_EQ(publishedTopics(d)[0].topic, "/magnetic");
  EXPECT_EQ(publishedTopics(d)[0].msg_type, "geometry_msgs/Vector3Stamped");
  EXPECT_EQ(publishedTopics(d)[0].rate, 0.0);  // every step
  // magnitude 1, inclination 60 degrees: (cos 60, 0, -sin 60) in north-west-up.
  EXPECT_NEAR((d.fieldWorld() - Eigen::Vector3d(0.5, 0, -0.8660254037844386)).norm(), 0, 1e-12);
  const HectorMagneticConfig c = parseHectorMagneticConfig(
      plugin("libhector_gazebo_ros_magnetic.so",
             {{"topicName", "magnetic/field"}, {"robotNamespace", "uav"}, {"bodyName", "base"},
              {"frameId", "mag"}, {"magnitude", "0.5"}, {"referenceHeading", "90"},
              {"declination", "30"}, {"inclination", "0"}, {"useMagneticFieldMsgs", "true"},
              {"gaussianNoise", "0.01 0.01 0.01"}, {"updateRate", "20"}}),
      "uav");
  EXPECT_EQ(publishedTopics(c)[0].topic, "/uav/magnetic/field");
  EXPECT_EQ(publishedTopics(c)[0].msg_type, "sensor_msgs/MagneticField");
  EXPECT_EQ(c.frame_id, "mag");
  EXPECT_EQ(c.model.gaussian_noise, Eigen::Vector3d::Constant(0.01));
  // h - d = 60 degrees: 0.5 (cos 60, sin 60, 0).
  EXPECT_NEAR((c.fieldWorld() - 0.5 * Eigen::Vector3d(0.5, std::sqrt(0.75), 0)).norm(), 0, 1e-12);
  // Yawed 90 degrees left, the body sees the north field on its -y.
  HectorMagnetic m(d);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d b = m.update(0.0, R);
  EXPECT_NEAR((b - Eigen::Vector3d(0, -0.5, -0.8660254037844386)).norm(), 0, 1e-12);
  EXPECT_NEAR(b.norm(), 1.0, 1e-12);
  EXPECT_NE(errorOf([] {
              parseHectorMagneticConfig(
                  plugin("libhector_gazebo_ros_magnetic.so", {{"useMagneticFieldMsgs", "yes"}}), "b");
            }).find("bot.urdf:12: hector magnetic plugin 'p' of model 'b': <useMagneticFieldMsgs> "
                    "'yes' is not a boolean"),
            std::string::npos);
}

TEST(HectorMagnetic, NoiseAndOffsetStatistics) {
  HectorMagneticConfig c;
  c.model.gaussian_noise = Eigen::Vector3d(0.01, 0.02, 0.03);
  c.model.offset = Eigen::Vector3d(0.1, 0, 0);
  c.seed = 9;
  HectorMagnetic m(c);
  const int n = 100000;
  Eigen::Vector3d s = Eigen::Vector3d::Zero(), ss = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector3d e = m.update(0.001, Eigen::Matrix3d::Identity()) - c.fieldWorld();
    s += e;
    ss += e.cwiseProduct(e);
  }
  EXPECT_NEAR(s.x() / n, 0.1, 1e-3);
  EXPECT_NEAR(std::sqrt(ss.y() / n), 0.02, 2e-4);
  EXPECT_NEAR(std::sqrt(ss.z() / n), 0.03, 3e-4);
}

// ---- libhector_gazebo_ros_sonar -------------------------------------------------------------

// A 3 x 3 grid over +-0.1 rad, 0.02 - 4 m.
const char* kSonarXml = R"(<sensor type="ray" name="sonar_front">
  <update_rate>20</update_rate>
  <ray>
    <scan>
      <horizontal><samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle></horizontal>
      <vertical><samples>3</samples><min_angle>-0.05</min_angle><max_angle>0.05</max_angle></vertical>
    </scan>
    <range><min>0.02</min><max>4</max><resolution>0.01</resolution></range>
  </ray>
  <plugin name="sonar" filename="libhector_gazebo_ros_sonar.so">PARAMS</plugin>
</sensor>)";

SensorSpec sonarSpec(const std::string& params, const std::string& type = "ray") {
  std::string xml = test::replaced(kSonarXml, "PARAMS", params);
  xml = test::replaced(xml, "type=\"ray\"", "type=\"" + type + "\"");
  return test::specFromXml(xml, "sonar_link_1", "bot.urdf", 30);
}

// A wall: a static box whose near face is the plane x = 1.5 (the sensor at the origin, along x).
Scene wall() {
  Scene scene;
  SceneBody b;
  b.name = "wall::link";
  b.model = "wall";
  b.is_static = true;
  const int body = scene.addBody(b);
  SceneItem box;
  box.body = body;
  box.X_BS.translation() = Eigen::Vector3d(1.6, 0, 0);
  box.shape.type = ShapeType::kBox;
  box.shape.size = Eigen::Vector3d(0.2, 10, 10);
  box.collision = true;
  box.visual = false;
  scene.items.push_back(box);
  return scene;
}

TEST(HectorSonarConfig, DefaultsParametersAndBadInput) {
  const SensorSpec spec = sonarSpec("");
  EXPECT_EQ(test::kindOf(spec), "hector_sonar");
  const HectorSonarConfig d = parseHectorSonarConfig(spec);
  EXPECT_EQ(d.topic(), "/sonar");
  EXPECT_EQ(d.frame_id, "sonar_link_1");  // ours: the link (upstream "/sonar_link")
  EXPECT_DOUBLE_EQ(d.timer.rate(), 10.0);  // the plugin's own timer, not <update_rate>
  EXPECT_EQ(publishedTopics(d)[0].msg_type, "sensor_msgs/Range");
  const HectorSonarConfig c = parseHectorSonarConfig(sonarSpec(
      "<robotNamespace>bot</robotNamespace><topicName>sonar_front</topicName>"
      "<frameId>/sonar_front_link</frameId><gaussianNoise>0.005</gaussianNoise>"
      "<offset>0.01</offset><updateRate>25</updateRate>"));
  EXPECT_EQ(c.topic(), "/bot/sonar_front");
  EXPECT_EQ(c.frame_id, "sonar_front_link");
  EXPECT_DOUBLE_EQ(c.model.gaussian_noise[0], 0.005);
  EXPECT_DOUBLE_EQ(c.model.offset[0], 0.01);
  EXPECT_DOUBLE_EQ(c.timer.rate(), 25.0);
  // A gpu_ray sensor: Gazebo's plugin casts its parent to RaySensor and refuses it.
  const SensorSpec gpu = sonarSpec("", "gpu_ray");
  EXPECT_EQ(test::kindOf(gpu), "hector_sonar");
  EXPECT_EQ(errorOf([&] { parseHectorSonarConfig(gpu); }),
            "bot.urdf:30: sensor 'sonar_front' of type 'gpu_ray': libhector_gazebo_ros_sonar "
            "needs a ray sensor (Gazebo refuses it)");
  EXPECT_NE(errorOf([] { parseHectorSonarConfig(sonarSpec("<gaussianNoise>-0.1</gaussianNoise>")); })
                .find("sensor 'sonar_front', plugin libhector_gazebo_ros_sonar.so: <gaussianNoise> "
                      "'-0.1' must be >= 0"),
            std::string::npos);
}

TEST(HectorSonar, NearestRayAgainstAWallAtAKnownDistance) {
  const Scene scene = wall();
  RayCaster caster;
  HectorSonarConfig c = parseHectorSonarConfig(sonarSpec(""));
  RayScanBuffers buffers;
  std::vector<float> ranges;
  shapeRanges(c.ray, caster, scene, Eigen::Isometry3d::Identity(), &buffers, &ranges);
  ASSERT_EQ(ranges.size(), 9u);
  std::mt19937_64 rng(1);
  HectorErrorModel1 model = c.model;
  RangeReading r = sonarReading(c, ranges, 0.1, &model, rng);
  EXPECT_NEAR(r.range, 1.5, 1e-5);  // the centre ray; the others are longer (1.5 / cos)
  EXPECT_EQ(r.radiation, Radiation::kUltrasound);
  EXPECT_FLOAT_EQ(r.field_of_view, 0.1f);  // min(0.2 horizontal, 0.1 vertical)
  EXPECT_FLOAT_EQ(r.min_range, 0.02f);
  EXPECT_FLOAT_EQ(r.max_range, 4.0f);
  // Seen from 3 m further back, nothing within range max: range max, the model not updated.
  Eigen::Isometry3d back = Eigen::Isometry3d::Identity();
  back.translation().x() = -3.0;
  shapeRanges(c.ray, caster, scene, back, &buffers, &ranges);
  model.offset[0] = 0.5;
  r = sonarReading(c, ranges, 0.1, &model, rng);
  EXPECT_FLOAT_EQ(r.range, 4.0f);
  EXPECT_EQ(model.current_error[0], 0.0);
  // In range, the model's offset applies; clipped to [min, max].
  shapeRanges(c.ray, caster, scene, Eigen::Isometry3d::Identity(), &buffers, &ranges);
  EXPECT_NEAR(sonarReading(c, ranges, 0.1, &model, rng).range, 2.0, 1e-5);
  model.offset[0] = -5.0;
  EXPECT_FLOAT_EQ(sonarReading(c, ranges, 0.1, &model, rng).range, 0.02f);
  model.offset[0] = 5.0;
  EXPECT_FLOAT_EQ(sonarReading(c, ranges, 0.1, &model, rng).range, 4.0f);
}

TEST(HectorSonar, NoiseStatisticsWithAFixedSeed) {
  const Scene scene = wall();
  RayCaster caster;
  const HectorSonarConfig c =
      parseHectorSonarConfig(sonarSpec("<gaussianNoise>0.01</gaussianNoise>"));
  RayScanBuffers buffers;
  std::vector<float> ranges;
  shapeRanges(c.ray, caster, scene, Eigen::Isometry3d::Identity(), &buffers, &ranges);
  std::mt19937_64 rng(c.seed);
  HectorErrorModel1 model = c.model;
  model.reset(rng);
  const int n = 100000;
  double s = 0, ss = 0;
  for (int k = 0; k < n; ++k) {
    const double e = sonarReading(c, ranges, 0.1, &model, rng).range - 1.5;
    s += e;
    ss += e * e;
  }
  EXPECT_NEAR(s / n, 0.0, 2e-4);
  EXPECT_NEAR(std::sqrt(ss / n), 0.01, 1e-4);
}

}  // namespace
}  // namespace tianracer_sim
