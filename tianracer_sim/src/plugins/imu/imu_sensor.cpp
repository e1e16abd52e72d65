// IMU: <sensor type="imu"> and libgazebo_ros_imu_sensor / libgazebo_ros_imu -> ImuConfig, and
// the measurement model (see imu_sensor.h).
//
// Differences from Gazebo, on purpose:
//  - libgazebo_ros_imu (the model plugin) reports like the sensor: body rates and specific
//    force in the body frame. Gazebo's GazeboRosIMU leaves gravity out of the acceleration and
//    rotates world-frame vectors by the body rotation instead of its inverse;
//  - robotNamespace is resolved as a namespace (ns + topicName), where libgazebo_ros_imu_sensor
//    concatenates strings (the same topic in every usual case);
//  - a libgazebo_ros_imu_sensor without <frameName> publishes in the link's frame (Gazebo does
//    not load it);
//  - covariances add the SDF noise variance of each axis to gaussianNoise^2.
#include "tianracer_sim/plugins/imu/imu_sensor.h"

#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/plugin_reader.h"

#include <cmath>

#include <tinyxml2.h>

namespace tianracer_sim {

namespace {

using tinyxml2::XMLElement;


// The reader reads a printed copy of the <sensor> (SensorSpec::xml) that knows each element's
// line of the model file: a message is placed at its element (the sensor's line for nullptr).
// Numbers of elements: NaN and inf are kept (validate() names them), garbage is an error.
// The plugins' parameters are read by the PluginReader, which refuses NaN and inf at once.
double number(const XmlReader& r, const XMLElement* e) { return r.anyNumber(e, ""); }
void readNoise(XmlReader& r, const XMLElement* noise, ImuAxisNoise* n, const std::string& where) {
  n->type = "gaussian";  // SDF's default
  if (noise->Attribute("type")) n->type = attributeText(noise, "type");
  for (const XMLElement* k = noise->FirstChildElement(); k; k = k->NextSiblingElement()) {
    const std::string key = k->Name();
    if (key == "type") n->type = elementText(k);
    else if (key == "mean") n->mean = number(r, k);
    else if (key == "stddev") n->stddev = number(r, k);
    else if (key == "bias_mean") n->bias_mean = number(r, k);
    else if (key == "bias_stddev") n->bias_stddev = number(r, k);
    else if (key == "precision") n->precision = number(r, k);
    else r.warn(k, where + "<noise><" + key + "> is not supported, ignored");
  }
  if (n->type != "none" && n->type != "gaussian" && n->type != "gaussian_quantized")
    r.fail(noise, where + "<noise> type '" + n->type +
           "' is not supported (none, gaussian, gaussian_quantized)");
}

void readImu(XmlReader& r, const XMLElement* imu, ImuConfig& c) {
  for (const XMLElement* e = imu->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "angular_velocity" || tag == "linear_acceleration") {
      auto& axes = tag == "angular_velocity" ? c.rate_noise : c.accel_noise;
      for (const XMLElement* a = e->FirstChildElement(); a; a = a->NextSiblingElement()) {
        const std::string axis = a->Name();
        const int i = axis == "x" ? 0 : axis == "y" ? 1 : axis == "z" ? 2 : -1;
        if (i < 0) {
          r.warn(a, "<" + tag + "><" + axis + "> is not supported, ignored");
          continue;
        }
        if (const XMLElement* noise = a->FirstChildElement("noise"))
          readNoise(r, noise, &axes[i], "<" + tag + "><" + axis + ">");
      }
    } else if (tag == "noise") {
      // SDF 1.4: one <noise><type> with <rate> and <accel> for all three axes.
      std::string type = "gaussian";
      if (const XMLElement* t = e->FirstChildElement("type")) type = elementText(t);
      for (const XMLElement* k = e->FirstChildElement(); k; k = k->NextSiblingElement()) {
        const std::string key = k->Name();
        if (key == "type") continue;
        if (key != "rate" && key != "accel") {
          r.warn(k, "<imu><noise><" + key + "> is not supported, ignored");
          continue;
        }
        ImuAxisNoise n;
        readNoise(r, k, &n, "<imu><noise><" + key + ">");
        n.type = type;
        if (type != "none" && type != "gaussian" && type != "gaussian_quantized")
          r.fail(e, "<imu><noise> type '" + type +
                 "' is not supported (none, gaussian, gaussian_quantized)");
        (key == "rate" ? c.rate_noise : c.accel_noise).fill(n);
      }
    } else {  // orientation_reference_frame, enable_orientation, topic and the unknown
      r.warn(e, "<imu><" + tag + "> is not supported, ignored");
    }
  }
}

// What libgazebo_ros_imu_sensor and libgazebo_ros_imu both read, the rate under each one's name.
void readImuPlugin(PluginReader& r, const char* rate_key, ImuConfig& c) {
  c.has_plugin = true;
  c.plugin_filename = r.plugin().filename;
  r.robotNamespace(NamespaceRule::kAsGiven, &c.robot_namespace);
  r.text("topicName", &c.topic_name);
  r.text("frameName", &c.frame_name);
  r.number(rate_key, &c.plugin_rate);
  r.number("gaussianNoise", &c.gaussian_noise);
  r.vector3("xyzOffset", &c.xyz_offset);
  r.vector3("rpyOffset", &c.rpy_offset);
}

void readSensorPlugin(const PluginSpec& p, const std::string& context, const WarningSink& warn,
                      const std::string& model_name, ImuConfig& c) {
  PluginReader r(p, context, warn);
  c.robot_namespace = "/" + model_name;  // Gazebo: the model's name
  c.topic_name = "imu_data";
  c.frame_name.clear();
  c.plugin_rate = 1.0;  // libgazebo_ros_imu_sensor's default updateRateHZ
  readImuPlugin(r, "updateRateHZ", c);
  r.boolean("initialOrientationAsReference", &c.initial_orientation_as_reference);
  r.ignore({"bodyName"});  // not read by the plugin either
  r.finish();
  if (c.frame_name.empty()) {
    r.warn(r.fileName() + " has no <frameName> (Gazebo does not load it): frame '" + c.link +
           "' used");
    c.frame_name = c.link;
  }
}

}  // namespace

double ImuConfig::publishRate() const {
  if (update_rate > 0.0 && plugin_rate > 0.0) return std::min(update_rate, plugin_rate);
  return update_rate > 0.0 ? update_rate : plugin_rate;
}

ImuConfig parseImuSensorConfig(const SensorSpec& spec, const std::string& model_name,
                               const WarningSink& warn) {
  const std::string context =
      "IMU sensor '" + spec.name + "' on link '" + spec.link + "' of model '" + model_name + "'";
  XmlReader r = XmlReader::copyOf(spec.source, spec.line, context + ": ", warn, spec.xml_lines);
  if (spec.type != "imu") r.fail(nullptr, "type '" + spec.type + "' is not an IMU");
  ImuConfig c;
  c.name = spec.name;
  c.link = spec.link;
  c.X_LS = spec.X_LS;
  c.update_rate = spec.update_rate;
  tinyxml2::XMLDocument doc;
  const XMLElement* sensor = r.parseCopy(spec.xml, &doc);
  for (const XMLElement* e = sensor->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Name();
    if (tag == "imu") {
      readImu(r, e, c);
    } else if (tag == "pose" || tag == "update_rate" || tag == "always_on" || tag == "plugin" ||
               tag == "visualize" || tag == "topic") {
      // The common fields, read once into the SensorSpec (a bad <update_rate> is its error).
    } else {
      r.warn(e, "<" + tag + "> is not supported, ignored");
    }
  }
  for (const PluginSpec& p : spec.plugins) {
    if (baseName(p.filename) == "libgazebo_ros_imu_sensor.so") {
      readSensorPlugin(p, context, warn, model_name, c);
    } else {
      r.warn(nullptr, "plugin '" + p.filename + "' is not supported on an IMU sensor, ignored");
    }
  }
  validate(c);
  return c;
}

ImuConfig parseImuPluginConfig(const SensorSpec& spec, const std::string& model_name,
                               const WarningSink& warn) {
  const std::string context = "IMU plugin '" + spec.name + "' of model '" + model_name + "'";
  if (spec.plugins.size() != 1)
    throw InputError(SourceLocation{spec.source, spec.line, "plugin"}, context + ": expected one plugin");
  const PluginSpec& p = spec.plugins.front();
  PluginReader r(p, context, warn);
  ImuConfig c;
  c.name = spec.name;
  c.model_plugin = true;
  c.topic_name = "/default_imu";
  c.service_name = "/default_imu";
  readImuPlugin(r, "updateRate", c);
  r.text("serviceName", &c.service_name);
  r.text("bodyName", &c.link);
  r.ignore({"alwaysOn"});
  r.finish();
  if (c.link.empty()) r.fail("<bodyName> is missing (Gazebo does not load the plugin without it)");
  if (c.frame_name.empty()) c.frame_name = c.link;
  validate(c);
  return c;
}

void validate(const ImuConfig& c) {
  const std::string what = (c.model_plugin ? "IMU plugin '" : "IMU sensor '") + c.name + "'";
  auto rate = [&](double v, const std::string& name) {
    if (!std::isfinite(v) || v < 0.0)
      throw SensorError(what + ": " + name + " " + formatNumber(v) + " must be a finite number >= 0");
  };
  rate(c.update_rate, "<update_rate>");
  rate(c.plugin_rate, c.model_plugin ? "<updateRate>" : "<updateRateHZ>");
  if (!std::isfinite(c.gaussian_noise) || c.gaussian_noise < 0.0)
    throw SensorError(what + ": <gaussianNoise> " + formatNumber(c.gaussian_noise) + " must be >= 0");
  if (!c.X_LS.matrix().allFinite()) throw SensorError(what + ": <pose> is not finite");
  if (!c.xyz_offset.allFinite() || !c.rpy_offset.allFinite())
    throw SensorError(what + ": <xyzOffset>/<rpyOffset> is not finite");
  for (int k = 0; k < 6; ++k) {
    const ImuAxisNoise& n = k < 3 ? c.rate_noise[k] : c.accel_noise[k - 3];
    const std::string where = std::string(k < 3 ? "<angular_velocity>" : "<linear_acceleration>") +
                              "<" + "xyz"[k % 3] + "><noise>";
    if (n.type != "none" && n.type != "gaussian" && n.type != "gaussian_quantized")
      throw SensorError(what + ": " + where + " type '" + n.type + "' is not supported");
    for (double v : {n.mean, n.stddev, n.bias_mean, n.bias_stddev, n.precision})
      if (!std::isfinite(v)) throw SensorError(what + ": " + where + " has a value " + formatNumber(v));
    if (n.stddev < 0.0 || n.bias_stddev < 0.0 || n.precision < 0.0)
      throw SensorError(what + ": " + where + " stddev, bias_stddev and precision must be >= 0");
  }
}

std::vector<SensorTopic> publishedTopics(const ImuConfig& c) {
  if (!c.has_plugin || c.topic_name.empty()) return {};
  return {{c.topic(), "sensor_msgs/Imu", c.publishRate()}};
}

ImuSensor::ImuSensor(ImuConfig config, const Eigen::Vector3d& gravity_W)
    : config_(std::move(config)), gravity_W_(gravity_W), rng_(config_.seed) {
  validate(config_);
  q_offset_ = Eigen::AngleAxisd(config_.rpy_offset.z(), Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(config_.rpy_offset.y(), Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(config_.rpy_offset.x(), Eigen::Vector3d::UnitX());
  // Biases once per sensor, as Gazebo's GaussianNoiseModel: N(bias_mean, bias_stddev), sign
  // flipped with probability 1/2.
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  for (int k = 0; k < 6; ++k) {
    const ImuAxisNoise& n = k < 3 ? config_.rate_noise[k] : config_.accel_noise[k - 3];
    if (!n.enabled()) continue;
    double b = n.bias_mean;
    if (n.bias_stddev > 0.0) b += std::normal_distribution<double>(0.0, n.bias_stddev)(rng_);
    if (coin(rng_) < 0.5) b = -b;
    bias_[k] = b;
  }
  const double gn2 = config_.gaussian_noise * config_.gaussian_noise;
  for (int i = 0; i < 3; ++i) {
    reading_.orientation_covariance[4 * i] = gn2;
    reading_.angular_velocity_covariance[4 * i] =
        gn2 + (config_.rate_noise[i].enabled() ? std::pow(config_.rate_noise[i].stddev, 2) : 0.0);
    reading_.linear_acceleration_covariance[4 * i] =
        gn2 + (config_.accel_noise[i].enabled() ? std::pow(config_.accel_noise[i].stddev, 2) : 0.0);
  }
}

void ImuSensor::reset() {
  steps_ = 0;
  have_sample_ = false;
  w_S_.setZero();
  v_W_.setZero();
}

void ImuSensor::record(double t, const Eigen::Isometry3d& X_WL) {
  const Eigen::Isometry3d X_WS = X_WL * config_.X_LS;
  const Eigen::Vector3d p = X_WS.translation();
  const Eigen::Matrix3d R = X_WS.linear();
  if (steps_ == 0) {
    if (config_.initial_orientation_as_reference) q_ref_inv_ = Eigen::Quaterniond(R).conjugate();
  } else if (t > t_) {
    const double dt = t - t_;
    v_W_ = (p - p_W_) / dt;
    const Eigen::AngleAxisd turn(R_WS_.transpose() * R);
    w_S_ = turn.axis() * (turn.angle() / dt);
  }
  if (steps_ < 2) ++steps_;
  t_ = t;
  p_W_ = p;
  R_WS_ = R;
}

double ImuSensor::noisy(double value, const ImuAxisNoise& n, double bias) {
  if (n.enabled()) {
    value += bias;
    if (n.stddev > 0.0) value += std::normal_distribution<double>(n.mean, n.stddev)(rng_);
    else value += n.mean;
    if (n.type == "gaussian_quantized" && n.precision > 0.0)
      value = std::round(value / n.precision) * n.precision;
  }
  if (config_.gaussian_noise > 0.0)
    value += std::normal_distribution<double>(0.0, config_.gaussian_noise)(rng_);
  return value;
}

void ImuSensor::skip() {
  have_sample_ = steps_ >= 2;
  t_sample_ = t_;
  v_sample_ = v_W_;
}

const ImuReading& ImuSensor::read() {
  // Mean acceleration since the previous sample; the last step's before any sample.
  Eigen::Vector3d a_W = Eigen::Vector3d::Zero();
  if (have_sample_ && t_ > t_sample_) a_W = (v_W_ - v_sample_) / (t_ - t_sample_);
  skip();
  const Eigen::Vector3d f_S = R_WS_.transpose() * (a_W - gravity_W_);
  for (int i = 0; i < 3; ++i) {
    reading_.angular_velocity[i] = noisy(w_S_[i], config_.rate_noise[i], bias_[i]);
    reading_.linear_acceleration[i] = noisy(f_S[i], config_.accel_noise[i], bias_[3 + i]);
  }
  Eigen::Quaterniond q(R_WS_);
  if (config_.initial_orientation_as_reference) q = q_ref_inv_ * q;
  q = (q_offset_ * q).normalized();
  reading_.orientation_xyzw = Eigen::Vector4d(q.x(), q.y(), q.z(), q.w());
  if (!config_.model_plugin && config_.gaussian_noise > 0.0) {
    std::normal_distribution<double> gauss(0.0, config_.gaussian_noise);
    for (int i = 0; i < 4; ++i) reading_.orientation_xyzw[i] += gauss(rng_);
  }
  return reading_;
}

}  // namespace tianracer_sim
