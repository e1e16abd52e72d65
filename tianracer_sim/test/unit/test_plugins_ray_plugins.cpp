// libgazebo_ros_range and libgazebo_ros_block_laser: their parameters as upstream reads them,
// the bad values, the nearest-beam range with its noise cap, the block laser's interpolation,
// point placement and REP 117 clipping, and Gazebo's shape ranges against a known box.
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/plugins/ray/ray_plugins.h"
#include "tianracer_sim/scene/scene.h"

#include "common_test_support.h"

namespace tianracer_sim {
namespace {

// gazebo_ros_pkgs' gazebo_ros_range.world sonar: a 5 x 5 grid over +-0.25 rad, 0.01 - 0.75 m.
const char* kSonar = R"(<sensor type="ray" name="sonar">
  <pose>0.25 0 0 0 0 0</pose>
  <update_rate>5</update_rate>
  <ray>
    <scan>
      <horizontal><samples>5</samples><resolution>1.0</resolution>
        <min_angle>-0.25</min_angle><max_angle>0.25</max_angle></horizontal>
      <vertical><samples>5</samples><resolution>1</resolution>
        <min_angle>-0.25</min_angle><max_angle>0.25</max_angle></vertical>
    </scan>
    <range><min>0.01</min><max>0.75</max><resolution>0.01</resolution></range>
  </ray>
</sensor>)";

SensorSpec sensor(const std::string& plugin, std::map<std::string, std::string> params,
                  const std::string& xml = kSonar) {
  SensorSpec s;
  s.name = "sonar";
  s.type = "ray";
  s.link = "link_1";
  s.X_LS.translation().x() = 0.25;
  s.update_rate = 5;
  s.xml = xml;
  s.source = "range.world";
  s.line = 40;
  PluginSpec p;
  p.name = "p";
  p.filename = plugin;
  p.params = std::move(params);
  p.source = "range.world";
  p.line = 52;  // the <plugin> inside the <sensor>
  s.plugins.push_back(p);
  return s;
}

SensorSpec sonar(std::map<std::string, std::string> params) {
  return sensor("libgazebo_ros_range.so", std::move(params));
}

template <typename F>
std::string errorOf(F f) {
  return test::errorText<SensorError>([&] { f(); }, "(no error)");
}

TEST(RangeConfig, ParametersAsGazeboRosRangeReadsThem) {
  std::vector<std::string> warnings;
  const RangeConfig c = parseRangeConfig(
      sonar({{"gaussianNoise", "0.005"}, {"alwaysOn", "true"}, {"updateRate", "5"},
             {"topicName", "sonar"}, {"frameName", "sonar_link"}, {"fov", "0.5"},
             {"radiation", "ultrasound"}}),
      [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  EXPECT_EQ(c.topic_name, "sonar");
  EXPECT_EQ(c.frame_name, "sonar_link");
  EXPECT_EQ(c.radiation, Radiation::kUltrasound);
  EXPECT_DOUBLE_EQ(c.fov, 0.5);
  EXPECT_DOUBLE_EQ(c.gaussian_noise, 0.005);
  EXPECT_EQ(c.ray.samples, 5);
  EXPECT_EQ(c.ray.vertical_samples, 5);
  EXPECT_DOUBLE_EQ(c.ray.range_max, 0.75);
  EXPECT_DOUBLE_EQ(c.publishRate(), 5.0);
  const std::vector<SensorTopic> topics = publishedTopics(c);
  ASSERT_EQ(topics.size(), 1u);
  EXPECT_EQ(topics[0].topic, "/sonar");
  EXPECT_EQ(topics[0].msg_type, "sensor_msgs/Range");
}

TEST(RangeConfig, DefaultsAndTheGridsFieldOfView) {
  const RangeConfig c = parseRangeConfig(sonar({}));
  EXPECT_EQ(c.topic_name, "/range");  // upstream's default
  EXPECT_EQ(c.frame_name, "link_1");  // ours: the link (upstream "/world")
  EXPECT_EQ(c.radiation, Radiation::kUltrasound);
  EXPECT_DOUBLE_EQ(c.fov, 0.5);  // without <fov>: the horizontal span, -0.25 .. 0.25
  EXPECT_DOUBLE_EQ(c.gaussian_noise, 0.0);
  const RangeConfig ir = parseRangeConfig(
      sonar({{"radiation", "infrared"}, {"robotNamespace", "bot"}, {"frameName", "/ir"},
             {"topicName", "ir"}}));
  EXPECT_EQ(ir.radiation, Radiation::kInfrared);
  EXPECT_EQ(ir.frame_name, "ir");
  EXPECT_EQ(publishedTopics(ir)[0].topic, "/bot/ir");
  EXPECT_EQ(publishedTopics(c)[0].topic, "/range");  // absolute: no namespace applies
  // updateRate throttles below the sensor rate only.
  EXPECT_DOUBLE_EQ(parseRangeConfig(sonar({{"updateRate", "2"}})).publishRate(), 2.0);
  EXPECT_DOUBLE_EQ(parseRangeConfig(sonar({{"updateRate", "50"}})).publishRate(), 5.0);
}

TEST(RangeConfig, BadInputNamesSensorElementAndValue) {
  std::vector<std::string> warnings;
  const RangeConfig c = parseRangeConfig(sonar({{"radiation", "laser"}, {"colour", "red"}}),
                                         [&](const std::string& w) { warnings.push_back(w); });
  EXPECT_EQ(c.radiation, Radiation::kInfrared);  // as upstream: anything else is infrared
  ASSERT_EQ(warnings.size(), 2u);
  // Placed at the <plugin>'s line, as every plugin parameter's message (PluginReader).
  EXPECT_NE(warnings[0].find("range.world:52: sensor 'sonar', plugin libgazebo_ros_range.so: "
                             "<radiation> 'laser'"),
            std::string::npos)
      << warnings[0];
  EXPECT_NE(warnings[1].find("<colour> is not a parameter of libgazebo_ros_range.so, ignored"),
            std::string::npos)
      << warnings[1];
  std::string e = errorOf([] { parseRangeConfig(sonar({{"fov", "wide"}})); });
  EXPECT_NE(e.find("sensor 'sonar'"), std::string::npos) << e;
  EXPECT_NE(e.find("<fov> 'wide' is not a number"), std::string::npos) << e;
  e = errorOf([] { parseRangeConfig(sonar({{"fov", "7"}})); });
  EXPECT_NE(e.find("<fov> 7 rad is more than 2 pi"), std::string::npos) << e;
  e = errorOf([] { parseRangeConfig(sonar({{"gaussianNoise", "-0.1"}})); });
  EXPECT_NE(e.find("<gaussianNoise> -0.1 must be >= 0"), std::string::npos) << e;
  e = errorOf([] { parseRangeConfig(sonar({{"updateRate", "nan"}})); });
  EXPECT_NE(e.find("<updateRate> nan is not finite"), std::string::npos) << e;
  // The <ray> is the lidar's: its errors too.
  SensorSpec bad = sonar({});
  bad.xml.replace(bad.xml.find("<max>0.75"), 9, "<max>0.001");
  e = errorOf([&] { parseRangeConfig(bad); });
  EXPECT_NE(e.find("range <min> 0.01 must be < range <max> 0.001"), std::string::npos) << e;
}

TEST(RangeReading, NearestBeamWithNoiseCappedAtMax) {
  RangeConfig c = parseRangeConfig(sonar({{"radiation", "infrared"}}));
  std::mt19937_64 rng(1);
  std::vector<float> shape(25, 0.75f);
  shape[12] = 0.225f;
  shape[3] = 0.4f;
  RangeReading r = rangeReading(c, shape, rng);
  EXPECT_FLOAT_EQ(r.range, 0.225f);  // no noise configured
  EXPECT_FLOAT_EQ(r.min_range, 0.01f);
  EXPECT_FLOAT_EQ(r.max_range, 0.75f);
  EXPECT_FLOAT_EQ(r.field_of_view, 0.5f);
  EXPECT_EQ(r.radiation, Radiation::kInfrared);
  // Nothing in range: exactly max_range, no noise drawn.
  c.gaussian_noise = 0.1;
  std::vector<float> none(25, 0.75f);
  const std::mt19937_64 before = rng;
  EXPECT_EQ(rangeReading(c, none, rng).range, 0.75f);
  EXPECT_EQ(rng, before);
  // With noise: mean and spread as configured, never above max (no clip below min).
  double sum = 0.0, sum2 = 0.0;
  int capped = 0;
  std::vector<float> near(25, 0.75f);
  near[0] = 0.7f;
  for (int i = 0; i < 20000; ++i) {
    const float v = rangeReading(c, near, rng).range;
    ASSERT_LE(v, 0.75f);
    capped += v == 0.75f;
    sum += v;
    sum2 += v * v;
  }
  EXPECT_NEAR(capped / 20000.0, 0.31, 0.02);  // P(N(0, 0.1) > 0.05)
  std::vector<float> mid(25, 0.75f);
  mid[7] = 0.3f;
  sum = sum2 = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double v = rangeReading(c, mid, rng).range;
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / 20000, sd = std::sqrt(sum2 / 20000 - mean * mean);
  EXPECT_NEAR(mean, 0.3, 0.003);
  EXPECT_NEAR(sd, 0.1, 0.003);
}

// The clipping world's block laser: 50 x 50 rays over +-0.3 (yaw) and +-0.4 (pitch), 0.4 - 1 m.
std::string blockXml(int h, double h_res, int v, double v_res) {
  return "<sensor name='laser_profiler' type='ray'><update_rate>5</update_rate><ray>"
         "<range><min>0.4</min><max>1.0</max><resolution>0.001</resolution></range><scan>"
         "<horizontal><samples>" + std::to_string(h) + "</samples><resolution>" +
         std::to_string(h_res) + "</resolution><min_angle>-0.3</min_angle><max_angle>0.3"
         "</max_angle></horizontal><vertical><samples>" + std::to_string(v) +
         "</samples><resolution>" + std::to_string(v_res) + "</resolution><min_angle>-0.4"
         "</min_angle><max_angle>0.4</max_angle></vertical></scan>"
         "<noise><type>gaussian</type><mean>0</mean><stddev>0.001</stddev></noise></ray>"
         "<always_on>1</always_on><visualize>True</visualize></sensor>";
}

BlockLaserConfig blockLaser(int h = 50, double h_res = 1, int v = 50, double v_res = 1,
                            std::map<std::string, std::string> params = {
                                {"robotNamespace", "/"}, {"frameName", "test_block_laser_frame"},
                                {"topicName", "test_block_laser"}, {"alwaysOn", "true"}}) {
  return parseBlockLaserConfig(
      sensor("libgazebo_ros_block_laser.so", std::move(params), blockXml(h, h_res, v, v_res)));
}

TEST(BlockLaserConfig, ParametersAndTopic) {
  const BlockLaserConfig c = blockLaser();
  EXPECT_EQ(c.frame_name, "test_block_laser_frame");
  EXPECT_EQ(c.columns(), 50);
  EXPECT_EQ(c.rows(), 50);
  const std::vector<SensorTopic> t = publishedTopics(c);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].topic, "/test_block_laser");  // <robotNamespace>/</robotNamespace>
  EXPECT_EQ(t[0].msg_type, "sensor_msgs/PointCloud");
  EXPECT_DOUBLE_EQ(t[0].rate, 5.0);
  EXPECT_EQ(blockLaser(50, 1, 50, 1, {}).topic_name, "/world");  // upstream's default topic
  EXPECT_EQ(blockLaser(10, 2.5, 3, 1).columns(), 25);  // samples * resolution, truncated
  std::string e = errorOf([] { blockLaser(50, 1, 50, 1, {{"gaussianNoise", "-1"}}); });
  EXPECT_NE(e.find("sensor 'sonar'"), std::string::npos) << e;
  EXPECT_NE(e.find("plugin libgazebo_ros_block_laser.so: <gaussianNoise> -1 must be >= 0"),
            std::string::npos)
      << e;
  e = errorOf([] { blockLaser(50, 1, 50, 0); });
  EXPECT_NE(e.find("<vertical><resolution> 0 must be > 0"), std::string::npos) << e;
  e = errorOf([] { blockLaser(512, 100, 512, 1); });
  EXPECT_NE(e.find("is more than 4e6"), std::string::npos) << e;
}

TEST(BlockLaserCloud, GazebosPlacementAndClipping) {
  const BlockLaserConfig c = blockLaser(5, 1, 3, 1);
  std::mt19937_64 rng(3);
  std::vector<float> shape(15);
  for (int k = 0; k < 15; ++k) shape[k] = 0.5f + 0.01f * k;
  BlockCloud cloud;
  blockLaserCloud(c, shape, rng, &cloud);
  ASSERT_EQ(cloud.intensity.size(), 15u);
  ASSERT_EQ(cloud.xyz.size(), 45u);
  const double ystep = 0.6 / 4, pstep = 0.8 / 2;
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 5; ++i) {
      const int k = j * 5 + i;
      // One ray a point: the range of ray (i, j), placed half a step further (upstream's
      // 0.5 (hja + hjb)), except in the last column and row.
      const double yaw = -0.3 + (i < 4 ? i + 0.5 : 4) * ystep;
      const double pitch = -0.4 + (j < 2 ? j + 0.5 : 2) * pstep;
      const double r = shape[k];
      EXPECT_NEAR(cloud.xyz[3 * k], r * std::cos(pitch) * std::cos(yaw), 1e-6) << k;
      EXPECT_NEAR(cloud.xyz[3 * k + 1], r * std::cos(pitch) * std::sin(yaw), 1e-6) << k;
      EXPECT_NEAR(cloud.xyz[3 * k + 2], r * std::sin(pitch), 1e-6) << k;
      EXPECT_EQ(cloud.intensity[k], 0.0f);
    }
  }
  // Two points per ray horizontally: the in-between point interpolates its two rays.
  const BlockLaserConfig half = blockLaser(3, 2, 1, 1);
  ASSERT_EQ(half.columns(), 6);
  blockLaserCloud(half, {0.5f, 0.7f, 0.9f}, rng, &cloud);
  const auto range = [&](int k) {
    return std::sqrt(cloud.xyz[3 * k] * cloud.xyz[3 * k] + cloud.xyz[3 * k + 1] * cloud.xyz[3 * k + 1] +
                     cloud.xyz[3 * k + 2] * cloud.xyz[3 * k + 2]);
  };
  EXPECT_NEAR(range(0), 0.5, 1e-6);   // hb = 0
  EXPECT_NEAR(range(1), 0.58, 1e-6);  // hb = 0.4 between rays 0 and 1
  EXPECT_NEAR(range(5), 0.9, 1e-6);   // the last ray
  // REP 117: an interpolated range outside [min, max] is -inf / +inf.
  const BlockLaserConfig one = blockLaser(2, 1, 1, 1);
  blockLaserCloud(one, {0.3f, 1.5f}, rng, &cloud);
  EXPECT_TRUE(std::isinf(cloud.xyz[0]) && cloud.xyz[0] < 0);  // r < min: -inf (yaw 0: x)
  EXPECT_TRUE(std::isinf(cloud.xyz[3]) && cloud.xyz[3] > 0);  // r > max: +inf
}

TEST(BlockLaserCloud, NoiseOnXyzExceptAtMaxRangeAndOnIntensity) {
  const BlockLaserConfig c = blockLaser(2, 1, 1, 1, {{"gaussianNoise", "0.01"}});
  std::mt19937_64 rng(5);
  BlockCloud cloud;
  double s_int = 0.0, s2_int = 0.0, s2_x = 0.0;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    blockLaserCloud(c, {0.6f, 1.0f}, rng, &cloud);
    // Point 1 carries ray 1 at max range: exact, no noise.
    EXPECT_FLOAT_EQ(cloud.xyz[3], static_cast<float>(1.0 * std::cos(0.3)));
    EXPECT_FLOAT_EQ(cloud.xyz[4], static_cast<float>(1.0 * std::sin(0.3)));
    const double x0 = 0.6;  // ray 0's range, placed at yaw 0: upstream's half step
    s2_x += (cloud.xyz[0] - x0) * (cloud.xyz[0] - x0);
    s_int += cloud.intensity[0];
    s2_int += cloud.intensity[0] * cloud.intensity[0];
  }
  EXPECT_NEAR(std::sqrt(s2_x / n), 0.01, 0.0005);
  EXPECT_NEAR(s_int / n, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(s2_int / n), 0.01, 0.0005);
}

TEST(ShapeRanges, GazebosLaserShapeAgainstABox) {
  // The range world: a 5 cm box centred 0.5 m ahead of the origin, the sonar at 0.25 m.
  Scene scene;
  SceneBody b;
  b.name = "model_2::link_2";
  b.model = "model_2";
  b.is_static = true;
  const int body = scene.addBody(b);
  SceneItem box;
  box.body = body;
  box.X_BS.translation() = Eigen::Vector3d(0.5, 0, 0);
  box.shape.type = ShapeType::kBox;
  box.shape.size = Eigen::Vector3d(0.05, 0.05, 0.05);
  box.collision = true;
  box.visual = false;
  scene.items.push_back(box);
  RayCaster caster;
  const RangeConfig c = parseRangeConfig(sonar({}));
  Eigen::Isometry3d X_WS = Eigen::Isometry3d::Identity();
  X_WS.translation().x() = 0.25;
  RayScanBuffers buffers;
  std::vector<float> ranges;
  shapeRanges(c.ray, caster, scene, X_WS, &buffers, &ranges);
  ASSERT_EQ(ranges.size(), 25u);
  EXPECT_NEAR(ranges[12], 0.225, 1e-5);  // the centre ray (j = 2, i = 2) hits the near face
  for (int k = 0; k < 25; ++k) {
    if (k != 12) EXPECT_FLOAT_EQ(ranges[k], 0.75f) << k;  // the others miss: range max
  }
  std::mt19937_64 rng(0);
  EXPECT_NEAR(rangeReading(c, ranges, rng).range, 0.225, 1e-5);
  // From x = -0.5 the near face is 0.975 m away, beyond range max: every ray reads max.
  X_WS.translation().x() = -0.5;
  shapeRanges(c.ray, caster, scene, X_WS, &buffers, &ranges);
  for (float r : ranges) EXPECT_FLOAT_EQ(r, 0.75f);
  EXPECT_FLOAT_EQ(rangeReading(c, ranges, rng).range, 0.75f);
}

}  // namespace
}  // namespace tianracer_sim
