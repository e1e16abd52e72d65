// What hector_gazebo_plugins' sensors share (tu-darmstadt-ros-pkg/hector_gazebo, melodic-devel,
// hector_gazebo_plugins/include/hector_gazebo_plugins/): the error model of sensor_model.h and
// the schedule of update_timer.h. ROS-free.
//
// SensorModel_<T> (sensor_model.h), per component, with rng draws N(0, s) = s * N(0, 1):
//  - parameters <offset>, <drift>, <driftFrequency>, <gaussianNoise>, <scaleError> (with a
//    prefix: <accelOffset>, <accelDrift>, ...); defaults 0, 0, 1/3600, 0, 1;
//  - reset(): drift = N(0, drift), error = 0;  reset(v): drift = v, error = 0;
//  - update(dt): drift = exp(-dt f) drift + dt N(0, sqrt(2 f) drift);
//                error = offset + drift + N(0, gaussianNoise);
//  - operator()(value, dt) = value * scaleError + update(dt) (component-wise);
//  - bias = drift + offset.
// Upstream draws with rand() (Box-Muller); we draw from the sensor's own generator seeded from
// the simulation's seed, so runs repeat. Note what upstream's discretisation gives (we keep it):
// the drift's stationary variance is 2 f dt^2 drift^2 / (1 - exp(-2 f dt)), about dt drift^2
// for f dt << 1, not drift^2 (the noise is scaled by dt, not sqrt(dt)).
//
// UpdateTimer (update_timer.h): <updateRate> (period 1/rate, 0 = every step), or <updatePeriod>
// and <updateOffset> (sdf::Time: "sec nsec"; we also take one number of seconds); updates on
// the grid offset + k period; dt of an update is the time since the previous one, 0 at the
// first (and after a reset).
#ifndef TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_MODEL_H
#define TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_MODEL_H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include <Eigen/Core>

#include "tianracer_sim/common/schedule.h"
#include "tianracer_sim/model/robot_model.h"

namespace tianracer_sim {

class PluginReader;

/// hector's SensorModel_<T> for N components (N = 1: SensorModel, N = 3: SensorModel3).
template <int N>
struct HectorErrorModel {
  using Vec = Eigen::Matrix<double, N, 1>;
  Vec offset = Vec::Zero();
  Vec drift = Vec::Zero();
  Vec drift_frequency = Vec::Constant(1.0 / 3600.0);  // 1/s (time constant 1 h)
  Vec gaussian_noise = Vec::Zero();
  Vec scale_error = Vec::Ones();

  Vec current_drift = Vec::Zero();
  Vec current_error = Vec::Zero();

  /// reset(): a new drift N(0, drift) per component; error 0.
  void reset(std::mt19937_64& rng) {
    for (int i = 0; i < N; ++i) current_drift[i] = drift[i] * gauss(rng);
    current_error.setZero();
  }
  /// reset(value): the drift set to value; error 0 (upstream's calibrate and set_*_bias).
  void reset(const Vec& value) {
    current_drift = value;
    current_error.setZero();
  }
  /// update(dt): advances the drift (first-order Gauss-Markov, as upstream discretises it) and
  /// draws the noise; component by component, drift draw then noise draw.
  const Vec& update(double dt, std::mt19937_64& rng) {
    for (int i = 0; i < N; ++i) {
      const double f = drift_frequency[i];
      current_drift[i] = std::exp(-dt * f) * current_drift[i] +
                         dt * (std::sqrt(2.0 * f) * drift[i]) * gauss(rng);
      current_error[i] = offset[i] + current_drift[i] + gaussian_noise[i] * gauss(rng);
    }
    return current_error;
  }
  /// operator()(value, dt): value * scale_error + update(dt).
  Vec apply(const Vec& value, double dt, std::mt19937_64& rng) {
    const Vec& e = update(dt, rng);
    return value.cwiseProduct(scale_error) + e;
  }
  Vec bias() const { return current_drift + offset; }

  static double gauss(std::mt19937_64& rng) {
    return std::normal_distribution<double>(0.0, 1.0)(rng);
  }
};

using HectorErrorModel1 = HectorErrorModel<1>;
using HectorErrorModel3 = HectorErrorModel<3>;

/// Reads <prefixOffset>, <prefixDrift>, <prefixDriftFrequency>, <prefixGaussianNoise>,
/// <prefixScaleError> (no prefix: <offset>, <drift>, ...), as SensorModel_::Load: three numbers
/// each for N = 3, one for N = 1. Stricter than upstream, which keeps the default where a value
/// does not parse (a single number for a vector among them): a value that is not N finite
/// numbers, or a negative drift, driftFrequency or gaussianNoise, fails with the element and
/// value.
void readErrorModel(PluginReader& r, const std::string& prefix, HectorErrorModel1* model);
void readErrorModel(PluginReader& r, const std::string& prefix, HectorErrorModel3* model);

/// hector's UpdateTimer: the rate the plugin updates at and the sim times of its updates.
struct HectorUpdateTimer {
  double period = 0.0;  // s; 0 = every step
  double offset = 0.0;  // s; no update before it
  double rate() const { return period > 0.0 ? 1.0 / period : 0.0; }
};

/// Reads <updateRate>, <updatePeriod>, <updateOffset> as UpdateTimer::Load, over `timer`'s
/// defaults (the plugin's setUpdateRate before Load). A negative or non-finite value fails.
void readUpdateTimer(PluginReader& r, HectorUpdateTimer* timer);

/// The one <plugin> of a model plugin given as a SensorSpec (modelPluginSensor()); throws
/// SensorError at the spec's line when there is not exactly one.
const PluginSpec& hectorModelPlugin(const SensorSpec& spec, const std::string& context);

/// <useWorldSphericalCoordinates> (GPS, magnetometer): read; when true, a warning that the
/// world's <spherical_coordinates> are not read here and the plugin's own reference values
/// hold.
void readUseWorldSphericalCoordinates(PluginReader& r);

/// The schedule of a timer, and dt as UpdateTimer::getTimeSinceLastUpdate gives it.
class HectorClock {
 public:
  explicit HectorClock(const HectorUpdateTimer& timer = {}) { set(timer); }
  void set(const HectorUpdateTimer& timer) {
    schedule_.period = timer.period;
    schedule_.next = timer.offset;
    offset_ = timer.offset;
  }
  bool due(double t) { return schedule_.due(t); }
  /// At an update at t: the time since the last one (0 at the first), and t is the last now.
  double tick(double t) {
    const double dt = has_last_ ? t - last_ : 0.0;
    has_last_ = true;
    last_ = t;
    return dt;
  }
  /// Time went back to t (reset_simulation): the next update has dt 0 and comes at t, or at
  /// the offset when t is before it.
  void restart(double t) {
    has_last_ = false;
    schedule_.restart(std::max(t, offset_));
  }

 private:
  Schedule schedule_;
  double offset_ = 0.0;
  bool has_last_ = false;
  double last_ = 0.0;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_HECTOR_HECTOR_MODEL_H
