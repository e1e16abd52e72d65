// hector_gazebo_plugins' SensorModel_::Load and UpdateTimer::Load (hector_model.h).
#include "tianracer_sim/plugins/hector/hector_model.h"

#include <cmath>
#include <vector>

#include "tianracer_sim/common/text.h"
#include "tianracer_sim/common/xml_reader.h"
#include "tianracer_sim/model/plugin_reader.h"

namespace tianracer_sim {
namespace {

std::string key(const std::string& prefix, const char* bare, const char* suffix) {
  return prefix.empty() ? std::string(bare) : prefix + suffix;
}

// N finite numbers, or the reader fails naming the element and the value.
template <int N>
bool readValue(PluginReader& r, const std::string& name, Eigen::Matrix<double, N, 1>* out) {
  if constexpr (N == 3) {
    Eigen::Vector3d v;
    if (!r.vector3(name, &v)) return false;
    *out = v;
  } else {
    double v;
    if (!r.number(name, &v)) return false;
    (*out)[0] = v;
  }
  return true;
}

template <int N>
void readModel(PluginReader& r, const std::string& prefix, HectorErrorModel<N>* m) {
  const std::string offset = key(prefix, "offset", "Offset");
  const std::string drift = key(prefix, "drift", "Drift");
  const std::string frequency = key(prefix, "driftFrequency", "DriftFrequency");
  const std::string noise = key(prefix, "gaussianNoise", "GaussianNoise");
  const std::string scale = key(prefix, "scaleError", "ScaleError");
  readValue<N>(r, offset, &m->offset);
  readValue<N>(r, scale, &m->scale_error);
  const auto nonNegative = [&](const std::string& name, Eigen::Matrix<double, N, 1>* v) {
    if (!readValue<N>(r, name, v)) return;
    if ((v->array() < 0.0).any())
      r.fail("<" + name + "> '" + *r.text(name) + "' must be >= 0");
  };
  nonNegative(drift, &m->drift);
  nonNegative(frequency, &m->drift_frequency);
  nonNegative(noise, &m->gaussian_noise);
}

// sdf::Time as UpdateTimer reads it ("sec nsec"), or one number of seconds.
bool readTime(PluginReader& r, const std::string& name, double* out) {
  const std::optional<std::string> t = r.text(name);
  if (!t) return false;
  const auto v = parseNumbers(*t);
  if (!v || v->empty() || v->size() > 2)
    r.fail("<" + name + "> '" + *t + "' is not a time (seconds, or sec nsec)");
  double s = (*v)[0];
  if (v->size() == 2) s += (*v)[1] * 1e-9;
  if (!std::isfinite(s) || s < 0.0) r.fail("<" + name + "> '" + *t + "' must be a time >= 0");
  *out = s;
  return true;
}

}  // namespace

void readErrorModel(PluginReader& r, const std::string& prefix, HectorErrorModel1* model) {
  readModel<1>(r, prefix, model);
}

void readErrorModel(PluginReader& r, const std::string& prefix, HectorErrorModel3* model) {
  readModel<3>(r, prefix, model);
}

const PluginSpec& hectorModelPlugin(const SensorSpec& spec, const std::string& context) {
  if (spec.plugins.size() != 1)
    throw InputError(SourceLocation{spec.source, spec.line, "plugin"},
                     context + ": expected one plugin");
  return spec.plugins.front();
}

void readUseWorldSphericalCoordinates(PluginReader& r) {
  bool use = false;
  if (r.boolean("useWorldSphericalCoordinates", &use) && use)
    r.warn("<useWorldSphericalCoordinates> true: the world's <spherical_coordinates> are not "
           "read here; the plugin's reference values are used");
}

void readUpdateTimer(PluginReader& r, HectorUpdateTimer* timer) {
  double rate = 0.0;
  if (r.number("updateRate", &rate, true)) timer->period = rate > 0.0 ? 1.0 / rate : 0.0;
  readTime(r, "updatePeriod", &timer->period);
  readTime(r, "updateOffset", &timer->offset);
}

}  // namespace tianracer_sim
