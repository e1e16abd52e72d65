// <sensor type="ray"> -> RaySensorConfig, its validation, the range model (ray_sensor.h) and
// RaySensor.
//
// Rays start at <range><min>, as Gazebo's do: gazebo-classic gazebo/physics/MultiRayShape.cc
// (Init) builds each ray from start = pose + min * axis to end = pose + max * axis, the ODE
// colliders (physics/ode/ODEMultiRayShape.cc, UpdateCallback) test it against every collision
// of the world, the sensor's own link included, and GetRange() returns min + the hit's distance
// along the ray ("Add min range, because we measured from min range"): a distance from the
// sensor origin. So whatever lies nearer than range_min (the lidar's own housing) is not seen,
// a ray that starts inside a solid sees the solid's far side (ODE's ray-box and ray-cylinder
// colliders), and REP 117's masks (RaySensor.cc/GpuRaySensor.cc: r <= min -> -inf, r >= max ->
// +inf) leave -inf only for a surface at exactly range_min.
//
// Deliberate differences from Gazebo, documented here once:
//  - gpu_ray is cast as ray, against collisions; Gazebo's GPU laser (sensors/GpuRaySensor.cc)
//    renders visuals with range min as its cameras' near clip plane, so off a camera's axis it
//    sees through a little more than range min (range min / cos of the angle to the axis);
//  - <horizontal><resolution> other than 1 is accepted but rays = samples (Gazebo casts
//    samples*resolution rays and interpolates);
//  - <range><resolution> is not applied to ranges (neither does Gazebo's RaySensor);
//  - with <vertical><samples> > 1 the rays fan out in elevation too; that is a 3D lidar, whose
//    velodyne plugin keeps points strictly inside max(min_range, <range><min>) and
//    min(max_range, <range><max>) (velodyne_gazebo_plugins GazeboRosVelodyneLaser.cpp, OnScan);
//  - points carry intensity 0 (Gazebo: the surface's laser_retro, 0 by default);
//  - frameName defaults to the link name, not gazebo_ros_laser's "/world"; a leading '/' is
//    dropped (tf2 frame ids have none).
#include "tianracer_sim/plugins/ray/ray_sensor.h"
#include "tianracer_sim/common/input_limits.h"

#include "tianracer_sim/common/xml_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <tinyxml2.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/model/plugin_reader.h"
#include "tianracer_sim/plugins/sensor_registry.h"

namespace tianracer_sim {

namespace {

using tinyxml2::XMLElement;


class ConfigReader {
 public:
  ConfigReader(const SensorSpec& spec, const WarningSink& warn)
      : spec_(spec), warn_(warn), what_("sensor '" + spec.name + "'"),
        xml_(XmlReader::copyOf(spec.source, spec.line, what_ + ": ", warn, spec.xml_lines)) {}

  RaySensorConfig read();

 private:
  [[noreturn]] void fail(const XMLElement* e, const std::string& msg) const { xml_.fail(e, msg); }
  void unsupported(const XMLElement* e) { xml_.unsupported(e); }
  std::string text(const XMLElement* e) const { return elementText(e); }
  double number(const XMLElement* e) const {
    const std::string t = text(e);
    const auto v = parseNumber(t);
    if (!v) fail(e, "<" + std::string(e->Name()) + "> '" + t + "' is not a number");
    if (!std::isfinite(*v))
      fail(e, "<" + std::string(e->Name()) + "> '" + t + "' is not a finite number");
    return *v;
  }
  int integer(const XMLElement* e) const { return xml_.integer(e, ""); }
  void readRay(const XMLElement* ray, RaySensorConfig& c);
  /// validate(c), its error placed at the line of the element its message names ("<samples>",
  /// "range <min>": the longest label of places_ the message starts with).
  void validateAt(const RaySensorConfig& c) const;

  const SensorSpec& spec_;
  const WarningSink& warn_;
  std::string what_;
  XmlReader xml_;
  std::map<std::string, const XMLElement*> places_;  // validate()'s label -> element read
};

void ConfigReader::validateAt(const RaySensorConfig& c) const {
  try {
    validate(c);
  } catch (const SensorError& err) {
    const std::string prefix = what_ + ": ";
    std::string msg = err.message();
    if (msg.compare(0, prefix.size(), prefix) != 0) throw;
    msg.erase(0, prefix.size());
    const XMLElement* at = nullptr;
    std::size_t longest = 0;
    for (const auto& [label, e] : places_) {
      if (label.size() > longest && msg.compare(0, label.size(), label) == 0) {
        at = e;
        longest = label.size();
      }
    }
    xml_.fail(at, msg);  // nullptr: the <sensor>'s line
  }
}

RaySensorConfig ConfigReader::read() {
  if (spec_.type != "ray" && spec_.type != "gpu_ray")
    throw SensorError(what_ + ": type '" + spec_.type + "' is not a ray sensor");
  RaySensorConfig c;
  c.name = spec_.name;
  c.link = spec_.link;
  c.X_LS = spec_.X_LS;
  c.update_rate = spec_.update_rate;
  c.frame_name = spec_.link;

  tinyxml2::XMLDocument doc;
  const XMLElement* sensor = xml_.parseCopy(spec_.xml, &doc);
  bool have_ray = false;
  for (const XMLElement* e = sensor->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "ray") {
      readRay(e, c);
      have_ray = true;
    } else if (tag == "pose" || tag == "update_rate") {
      places_["<" + tag + ">"] = e;  // read in the SensorSpec
    } else if (tag == "always_on" ||
               tag == "plugin" || tag == "visualize") {
      // pose, rate and plugins come parsed in the SensorSpec; visualize means nothing headless.
    } else {
      unsupported(e);
    }
  }
  if (!have_ray) throw SensorError(what_ + ": no <ray> element");

  for (const PluginSpec& p : spec_.plugins) {
    const bool velodyne = p.filename.find("gazebo_ros_velodyne_laser") != std::string::npos ||
                          p.filename.find("gazebo_ros_velodyne_gpu_laser") != std::string::npos;
    const bool laser = p.filename.find("gazebo_ros_laser") != std::string::npos ||
                       p.filename.find("gazebo_ros_gpu_laser") != std::string::npos;
    if (velodyne) {
      c.has_ros_plugin = true;
      c.velodyne = true;
      c.topic_name = "/world";  // the plugin's defaults
      PluginReader r(p, what_, warn_);
      r.text("topicName", &c.topic_name);
      c.frame_name = r.frame("frameName", c.frame_name);
      r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
      r.number("min_range", &c.cloud_min_range);
      r.number("max_range", &c.cloud_max_range);
      r.number("gaussianNoise", &c.cloud_noise);
      r.finish();
      continue;
    }
    if (!laser) {
      // A plugin another kind of this sensor type registers (gazebo_ros_range,
      // gazebo_ros_block_laser, hector's sonar: plugins/sensor_registry.h) reads the same
      // <ray>; that kind's own parser reads its parameters.
      if (findPluginKind(spec_.type, p.filename)) continue;
      if (warn_)
        warn_(formatLocation(p.source, p.line) + what_ + ": plugin '" + p.filename +
              "' is not supported on a ray sensor, ignored");
      continue;
    }
    c.has_ros_plugin = true;
    PluginReader r(p, what_, warn_);
    r.text("topicName", &c.topic_name);
    c.frame_name = r.frame("frameName", c.frame_name);
    // gazebo_ros_laser.cpp / gazebo_ros_gpu_laser.cpp Load: GetRobotNamespace.
    c.namespace_from_model = r.robotNamespace(NamespaceRule::kEmptyIsModel, &c.robot_namespace) ==
                             NamespaceFrom::kModel;
    r.finish();
  }
  if (c.vertical_samples == 1 && (c.vertical_min_angle != 0.0 || c.vertical_max_angle != 0.0) &&
      warn_)
    warn_(what_ + ": <vertical> angles ignored with one vertical sample (planar scan)");
  validateAt(c);
  return c;
}

void ConfigReader::readRay(const XMLElement* ray, RaySensorConfig& c) {
  for (const XMLElement* e = ray->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "scan") {
      for (const XMLElement* s = e->FirstChildElement(); s; s = s->NextSiblingElement()) {
        const std::string stag = s->Name();
        const bool horizontal = stag == "horizontal";
        if (!horizontal && stag != "vertical") {
          unsupported(s);
          continue;
        }
        for (const XMLElement* k = s->FirstChildElement(); k; k = k->NextSiblingElement()) {
          const std::string key = k->Name();
          const bool resolution = horizontal && key == "resolution";
          places_[(horizontal && !resolution ? "" : "<" + stag + ">") + "<" + key + ">"] = k;
          if (horizontal) {
            if (key == "samples") c.samples = integer(k);
            else if (key == "resolution") c.resolution = number(k);
            else if (key == "min_angle") c.min_angle = number(k);
            else if (key == "max_angle") c.max_angle = number(k);
            else unsupported(k);
          } else if (key == "samples") {
            c.vertical_samples = integer(k);
          } else if (key == "min_angle") {
            c.vertical_min_angle = number(k);
          } else if (key == "max_angle") {
            c.vertical_max_angle = number(k);
          } else if (key == "resolution") {
            c.vertical_resolution = number(k);
          } else {
            unsupported(k);
          }
        }
      }
    } else if (tag == "range") {
      for (const XMLElement* k = e->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string key = k->Name();
        places_["range <" + key + ">"] = k;
        if (key == "min") c.range_min = number(k);
        else if (key == "max") c.range_max = number(k);
        else if (key == "resolution") c.range_resolution = number(k);
        else unsupported(k);
      }
    } else if (tag == "noise") {
      c.noise.type = "gaussian";  // SDF's default type for <ray><noise>
      places_["noise <type>"] = e;
      for (const XMLElement* k = e->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string key = k->Name();
        places_["noise <" + key + ">"] = k;
        if (key == "type") c.noise.type = text(k);
        else if (key == "mean") c.noise.mean = number(k);
        else if (key == "stddev") c.noise.stddev = number(k);
        else unsupported(k);
      }
    } else {
      unsupported(e);
    }
  }
}

}  // namespace

RaySensorConfig parseRaySensorConfig(const SensorSpec& spec, const WarningSink& warn) {
  ConfigReader reader(spec, warn);
  return reader.read();
}

void validate(const RaySensorConfig& c) {
  const std::string what = "sensor '" + c.name + "'";
  const std::pair<double, const char*> numbers[] = {
      {c.update_rate, "<update_rate>"},
      {c.resolution, "<horizontal><resolution>"},
      {c.min_angle, "<min_angle>"},
      {c.max_angle, "<max_angle>"},
      {c.vertical_min_angle, "<vertical><min_angle>"},
      {c.vertical_max_angle, "<vertical><max_angle>"},
      {c.range_min, "range <min>"},
      {c.range_max, "range <max>"},
      {c.range_resolution, "range <resolution>"},
      {c.noise.mean, "noise <mean>"},
      {c.noise.stddev, "noise <stddev>"}};
  for (const auto& [v, name] : numbers) {
    if (!std::isfinite(v)) throw SensorError(what + ": " + name + " " + formatNumber(v) + " is not finite");
  }
  if (!c.X_LS.matrix().allFinite()) throw SensorError(what + ": <pose> is not finite");
  if (c.samples <= 0)
    throw SensorError(what + ": <samples> must be > 0 (got " + std::to_string(c.samples) + ")");
  if (c.vertical_samples < 1 || c.vertical_samples > kMaxVerticalSamples)
    throw SensorError(what + ": <vertical><samples> " + std::to_string(c.vertical_samples) +
                      " out of range 1.." + std::to_string(kMaxVerticalSamples));
  // Each ray is a float per scan and an Embree query per update: 1e9 samples allocated 4 GB
  // and hung for minutes.
  if (static_cast<double>(c.samples) * c.vertical_samples > limits::kRaysPerScan)
    throw SensorError(what + ": <samples> " + std::to_string(c.samples) + " x <vertical><samples> " +
                      std::to_string(c.vertical_samples) + " rays per scan is out of range (<= " +
                      limits::formatNumber(limits::kRaysPerScan) + ")");
  if (c.vertical_min_angle > c.vertical_max_angle)
    throw SensorError(what + ": <vertical><min_angle> " + formatNumber(c.vertical_min_angle) +
                      " > <vertical><max_angle> " + formatNumber(c.vertical_max_angle));
  if (std::isnan(c.cloud_min_range) || std::isnan(c.cloud_max_range) ||
      !std::isfinite(c.cloud_noise) || c.cloud_noise < 0.0)
    throw SensorError(what + ": velodyne min_range, max_range or gaussianNoise is invalid");
  if (c.resolution <= 0.0)
    throw SensorError(what + ": <horizontal><resolution> must be > 0 (got " +
                      formatNumber(c.resolution) + ")");
  if (c.min_angle > c.max_angle)
    throw SensorError(what + ": <min_angle> " + formatNumber(c.min_angle) + " > <max_angle> " +
                      formatNumber(c.max_angle));
  if (c.range_min < 0.0)
    throw SensorError(what + ": range <min> must be >= 0 (got " + formatNumber(c.range_min) + ")");
  if (c.range_min >= c.range_max)
    throw SensorError(what + ": range <min> " + formatNumber(c.range_min) + " must be < range <max> " +
                      formatNumber(c.range_max));
  if (c.range_resolution < 0.0)
    throw SensorError(what + ": range <resolution> must be >= 0 (got " +
                      formatNumber(c.range_resolution) + ")");
  if (c.update_rate < 0.0)
    throw SensorError(what + ": <update_rate> must be >= 0 (got " + formatNumber(c.update_rate) + ")");
  if (c.noise.type != "none" && c.noise.type != "gaussian")
    throw SensorError(what + ": noise <type> '" + c.noise.type +
                      "' is not supported (gaussian or none)");
  if (c.noise.stddev < 0.0)
    throw SensorError(what + ": noise <stddev> must be >= 0 (got " + formatNumber(c.noise.stddev) + ")");
}

std::vector<SensorTopic> publishedTopics(const RaySensorConfig& c) {
  return {{resolveTopic(c.robot_namespace, c.topic_name),
           c.velodyne ? "sensor_msgs/PointCloud2" : "sensor_msgs/LaserScan", c.update_rate}};
}

void applyCloudRangeModel(const RaySensorConfig& c, std::mt19937_64& rng, float* ranges, int n) {
  const double lo = std::max(c.cloud_min_range, c.range_min);
  const double hi = std::min(c.cloud_max_range, c.range_max);
  const bool sdf_noise = c.noise.enabled();
  std::normal_distribution<double> gauss(c.noise.mean, c.noise.stddev > 0.0 ? c.noise.stddev : 1.0);
  std::normal_distribution<double> plugin(0.0, c.cloud_noise > 0.0 ? c.cloud_noise : 1.0);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < n; ++i) {
    double r = ranges[i];
    if (!std::isfinite(r)) {
      ranges[i] = nan;
      continue;
    }
    if (sdf_noise) r += c.noise.stddev > 0.0 ? gauss(rng) : c.noise.mean;
    if (c.cloud_noise > 0.0) r += plugin(rng);
    ranges[i] = (lo < r && r < hi) ? static_cast<float>(r) : nan;
  }
}

void applyRangeModel(const RaySensorConfig& c, std::mt19937_64& rng, float* ranges, int n) {
  const float inf = std::numeric_limits<float>::infinity();
  const bool noisy = c.noise.enabled();
  std::normal_distribution<double> gauss(c.noise.mean, c.noise.stddev > 0.0 ? c.noise.stddev : 1.0);
  for (int i = 0; i < n; ++i) {
    const double r = ranges[i];
    if (!(r < c.range_max)) {  // also NaN, which a caster never returns
      ranges[i] = inf;
    } else if (r <= c.range_min) {
      ranges[i] = -inf;
    } else if (noisy) {
      const double e = c.noise.stddev > 0.0 ? gauss(rng) : c.noise.mean;
      ranges[i] = static_cast<float>(std::clamp(r + e, c.range_min, c.range_max));
    }
  }
}

RaySensor::RaySensor(RaySensorConfig config) : config_(std::move(config)), rng_(config_.seed) {
  validate(config_);
  ranges_.reserve(config_.samples);
}

void castRayGrid(RayCaster& caster, const Scene& scene, const Eigen::Isometry3d& X_WS,
                 const RaySensorConfig& config, RayScanBuffers* buffers,
                 std::vector<float>* ranges) {
  RayScanBuffers& b = *buffers;
  caster.update(scene);
  const int samples = std::max(0, config.samples);
  const int rings = std::max(1, config.vertical_samples);
  const int n = samples * rings;
  ranges->resize(n);
  const double inc = config.angleIncrement();
  if (static_cast<int>(b.dirs_S.size()) != n || b.dirs_min != config.min_angle ||
      b.dirs_inc != inc || b.dirs_rings != rings || b.dirs_vmin != config.vertical_min_angle ||
      b.dirs_vmax != config.vertical_max_angle) {
    b.dirs_S.resize(n);
    for (int j = 0; j < rings; ++j) {
      const double p = config.verticalAngle(j);
      const double cp = rings > 1 ? std::cos(p) : 1.0, sp = rings > 1 ? std::sin(p) : 0.0;
      for (int i = 0; i < samples; ++i) {
        const double a = config.angle(i);
        b.dirs_S[j * samples + i] = Eigen::Vector3d(cp * std::cos(a), cp * std::sin(a), sp);
      }
    }
    b.dirs_min = config.min_angle;
    b.dirs_inc = inc;
    b.dirs_rings = rings;
    b.dirs_vmin = config.vertical_min_angle;
    b.dirs_vmax = config.vertical_max_angle;
  }
  b.dirs_W.resize(n);
  const Eigen::Matrix3d R_WS = X_WS.linear();
  for (int i = 0; i < n; ++i) b.dirs_W[i] = (R_WS * b.dirs_S[i]).cast<float>();
  // Rays start at range_min (Gazebo's MultiRayShape) and look a little past range_max:
  // anything there maps to +inf anyway.
  const float t_min = static_cast<float>(config.range_min);
  const float t_max = static_cast<float>(config.range_max * (1.0 + 1e-6) + 1e-6);
  caster.castRays(X_WS.translation(), b.dirs_W, t_min, t_max, ranges->data());
}

void scanRays(RayCaster& caster, const Scene& scene, const Eigen::Isometry3d& X_WS,
              const RaySensorConfig& config, std::mt19937_64& rng, RayScanBuffers* buffers,
              std::vector<float>* ranges) {
  castRayGrid(caster, scene, X_WS, config, buffers, ranges);
  const int n = static_cast<int>(ranges->size());
  if (config.velodyne) {
    applyCloudRangeModel(config, rng, ranges->data(), n);
  } else {
    applyRangeModel(config, rng, ranges->data(), n);
  }
}

void shapeRanges(const RaySensorConfig& config, RayCaster& caster, const Scene& scene,
                 const Eigen::Isometry3d& X_WS, RayScanBuffers* buffers,
                 std::vector<float>* ranges) {
  castRayGrid(caster, scene, X_WS, config, buffers, ranges);
  const float max = static_cast<float>(config.range_max);
  for (float& r : *ranges) r = std::min(r, max);  // +inf (no hit) too
}

std::vector<float> scanRays(RayCaster& caster, const Scene& scene, const Eigen::Isometry3d& X_WS,
                            const RaySensorConfig& config, std::mt19937_64& rng) {
  RayScanBuffers buffers;
  std::vector<float> ranges;
  scanRays(caster, scene, X_WS, config, rng, &buffers, &ranges);
  return ranges;
}

const std::vector<float>& RaySensor::scan(RayCaster& caster, const Scene& scene,
                                          const Eigen::Isometry3d& X_WL) {
  scanRays(caster, scene, X_WL * config_.X_LS, config_, rng_, &buffers_, &ranges_);
  return ranges_;
}

}  // namespace tianracer_sim
