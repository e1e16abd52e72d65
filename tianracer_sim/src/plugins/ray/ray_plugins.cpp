// libgazebo_ros_range and libgazebo_ros_block_laser (ray_plugins.h). Facts from
// gazebo_ros_pkgs noetic-devel gazebo_plugins/src/gazebo_ros_range.cpp (Load, PutRangeData)
// and gazebo_ros_block_laser.cpp (Load, PutLaserData), on gazebo-classic's
// physics/MultiRayShape.cc ranges (GetRange = min + hit distance along the ray, max when none).
//
// Deliberate differences:
//  - frameName defaults to the sensor's link (upstream "/world"), a leading '/' dropped, as for
//    our gazebo_ros_laser;
//  - range: without <fov> the field of view is the grid's horizontal span (upstream 0.05);
//  - block laser: intensities are 0 + noise (we do not model laser_retro); with one ray in a
//    direction the point sits on that ray (upstream divides by rays - 1 = 0: NaN); noise is
//    seeded from the simulation's seed (upstream: rand()).
#include "tianracer_sim/plugins/ray/ray_plugins.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {
namespace {

const PluginSpec* findPlugin(const SensorSpec& spec, const std::string& stem) {
  for (const PluginSpec& p : spec.plugins) {
    if (p.filename.find(stem) != std::string::npos) return &p;
  }
  return nullptr;
}

// What gazebo_ros_range and gazebo_ros_block_laser share: the ray sensor they sit on, their
// plugin (lib<stem>.so), and the names both read: robotNamespace, topicName and frameName (the
// sensor's link by default). The reader goes on with the plugin's own parameters.
template <class Config>
PluginReader readRayPlugin(const SensorSpec& spec, const std::string& stem,
                           const WarningSink& warn, Config* c) {
  c->ray = parseRaySensorConfig(spec, warn);
  const PluginSpec* p = findPlugin(spec, stem);
  if (!p) throw SensorError("sensor '" + spec.name + "': no lib" + stem + " plugin");
  PluginReader r(*p, "sensor '" + spec.name + "', plugin " + p->filename, warn);
  r.robotNamespace(NamespaceRule::kAsGiven, &c->robot_namespace);
  r.text("topicName", &c->topic_name);
  c->frame_name = r.frame("frameName", c->ray.link);
  return r;
}

}  // namespace

double RangeConfig::publishRate() const {
  if (update_rate > 0.0 && (ray.update_rate <= 0.0 || update_rate < ray.update_rate))
    return update_rate;
  return ray.update_rate;
}

RangeConfig parseRangeConfig(const SensorSpec& spec, const WarningSink& warn) {
  RangeConfig c;
  PluginReader r = readRayPlugin(spec, "gazebo_ros_range", warn, &c);
  c.fov = c.ray.max_angle - c.ray.min_angle;
  std::string radiation;
  if (r.text("radiation", &radiation)) {
    if (radiation == "ultrasound") {
      c.radiation = Radiation::kUltrasound;
    } else {
      c.radiation = Radiation::kInfrared;
      if (radiation != "infrared")
        r.warn("<radiation> '" + radiation + "' is neither ultrasound nor infrared: infrared, as "
               "gazebo_ros_range");
    }
  }
  r.number("fov", &c.fov, true);
  if (c.fov > 2.0 * M_PI) r.fail("<fov> " + formatNumber(c.fov) + " rad is more than 2 pi");
  r.number("gaussianNoise", &c.gaussian_noise, true);
  r.number("updateRate", &c.update_rate, true);
  r.ignore({"alwaysOn"});
  r.finish();
  return c;
}

std::vector<SensorTopic> publishedTopics(const RangeConfig& c) {
  return {{resolveTopic(c.robot_namespace, c.topic_name), "sensor_msgs/Range", c.publishRate()}};
}

RangeReading rangeReading(const RangeConfig& c, const std::vector<float>& shape_ranges,
                          std::mt19937_64& rng) {
  RangeReading out;
  out.min_range = static_cast<float>(c.ray.range_min);
  out.max_range = static_cast<float>(c.ray.range_max);
  out.field_of_view = static_cast<float>(c.fov);
  out.radiation = c.radiation;
  // Upstream starts from the largest float and keeps the smallest ray.
  float range = std::numeric_limits<float>::max();
  for (float r : shape_ranges) range = std::min(range, r);
  if (range < out.max_range) {
    std::normal_distribution<double> gauss(0.0, 1.0);
    const double noisy = range + c.gaussian_noise * gauss(rng);
    range = static_cast<float>(std::min(noisy, c.ray.range_max));
  }
  out.range = range;
  return out;
}

int BlockLaserConfig::columns() const {
  return std::max(1, static_cast<int>(ray.samples * ray.resolution));
}

int BlockLaserConfig::rows() const {
  return std::max(1, static_cast<int>(ray.vertical_samples * ray.vertical_resolution));
}

BlockLaserConfig parseBlockLaserConfig(const SensorSpec& spec, const WarningSink& warn) {
  BlockLaserConfig c;
  PluginReader r = readRayPlugin(spec, "gazebo_ros_block_laser", warn, &c);
  r.number("gaussianNoise", &c.gaussian_noise, true);
  r.number("hokuyoMinIntensity", &c.hokuyo_min_intensity);
  r.number("updateRate", &c.update_rate, true);
  r.ignore({"alwaysOn"});
  r.finish();
  if (!(c.ray.vertical_resolution > 0.0) || !std::isfinite(c.ray.vertical_resolution))
    throw SensorError("sensor '" + spec.name + "': <vertical><resolution> " +
                      formatNumber(c.ray.vertical_resolution) + " must be > 0");
  const double points = static_cast<double>(c.columns()) * c.rows();
  if (points > 4.0e6)
    throw SensorError("sensor '" + spec.name + "': a block laser of " + formatNumber(points) +
                      " points (samples x resolution, both directions) is more than 4e6");
  return c;
}

std::vector<SensorTopic> publishedTopics(const BlockLaserConfig& c) {
  return {{resolveTopic(c.robot_namespace, c.topic_name), "sensor_msgs/PointCloud",
           c.ray.update_rate}};
}

void blockLaserCloud(const BlockLaserConfig& c, const std::vector<float>& shape_ranges,
                     std::mt19937_64& rng, BlockCloud* out) {
  const RaySensorConfig& ray = c.ray;
  const int rays = std::max(1, ray.samples), rings = std::max(1, ray.vertical_samples);
  const int cols = c.columns(), rows = c.rows();
  const double min_range = ray.range_min, max_range = ray.range_max;
  const double inf = std::numeric_limits<double>::infinity();
  const double y_diff = ray.max_angle - ray.min_angle;
  const double p_diff = ray.vertical_max_angle - ray.vertical_min_angle;
  std::normal_distribution<double> gauss(0.0, 1.0);
  const auto noise = [&] { return c.gaussian_noise > 0.0 ? c.gaussian_noise * gauss(rng) : 0.0; };
  out->xyz.resize(static_cast<std::size_t>(cols) * rows * 3);
  out->intensity.resize(static_cast<std::size_t>(cols) * rows);
  std::size_t k = 0;
  for (int j = 0; j < rows; ++j) {
    double vb = rows == 1 ? 0.0 : static_cast<double>(j) * (rings - 1) / (rows - 1);
    const int vja = static_cast<int>(std::floor(vb));
    const int vjb = std::min(vja + 1, rings - 1);
    vb -= std::floor(vb);
    const double pitch = rings == 1 ? ray.verticalAngle(0)
                                    : 0.5 * (vja + vjb) * p_diff / (rings - 1) +
                                          ray.vertical_min_angle;
    for (int i = 0; i < cols; ++i, ++k) {
      double hb = cols == 1 ? 0.0 : static_cast<double>(i) * (rays - 1) / (cols - 1);
      const int hja = static_cast<int>(std::floor(hb));
      const int hjb = std::min(hja + 1, rays - 1);
      hb -= std::floor(hb);
      const double r1 = shape_ranges[hja + vja * rays], r2 = shape_ranges[hjb + vja * rays];
      const double r3 = shape_ranges[hja + vjb * rays], r4 = shape_ranges[hjb + vjb * rays];
      double r = (1 - vb) * ((1 - hb) * r1 + hb * r2) + vb * ((1 - hb) * r3 + hb * r4);
      if (r < min_range) {
        r = -inf;
      } else if (r > max_range) {
        r = inf;
      }
      const double yaw = rays == 1 ? ray.angle(0)
                                   : 0.5 * (hja + hjb) * y_diff / (rays - 1) + ray.min_angle;
      double x = r * std::cos(pitch) * std::cos(yaw);
      double y = r * std::cos(pitch) * std::sin(yaw);
      double z = r * std::sin(pitch);
      if (std::fabs(max_range - r) > 1e-6) {
        x += noise();
        y += noise();
        z += noise();
      }
      out->xyz[3 * k] = static_cast<float>(x);
      out->xyz[3 * k + 1] = static_cast<float>(y);
      out->xyz[3 * k + 2] = static_cast<float>(z);
      out->intensity[k] = static_cast<float>(0.0 + noise());
    }
  }
}

}  // namespace tianracer_sim
