// libgazebo_ros_p3d in the simulation, around its core (p3d.h).
#ifndef TIANRACER_SIM_PLUGINS_P3D_SIM_P3D_H
#define TIANRACER_SIM_PLUGINS_P3D_SIM_P3D_H

#include <string>

#include "tianracer_sim/plugins/p3d/p3d.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// libgazebo_ros_p3d: a link's ground truth, optionally relative to another link.
class SimP3d : public SimCoreSensor<P3dSensor, P3dReading> {
 public:
  static constexpr SensorOutputs kReading = kOutput;
  SimP3d(const SimSensorSetup& setup, P3dConfig config);
  const P3dReading& reading() const { return output(); }
  /// The frame the reading is in (world, or the reference link with its tf_prefix) and the
  /// link's own frame.
  const std::string& frame() const { return frame_; }
  const std::string& childFrame() const { return child_; }

  void sample(SensorOutputs outputs, SensorWorld& world) override;

 private:
  // Velocities of links off the root body are pose differences: the history is kept each step.
  void track(double t, SensorWorld& world) override;
  void forget() override;
  void track(double t, SensorWorld& world, const std::string& link, LinkMotion* motion);
  std::string frame_, child_;
  LinkMotion body_, reference_;
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& p3dKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_P3D_SIM_P3D_H
