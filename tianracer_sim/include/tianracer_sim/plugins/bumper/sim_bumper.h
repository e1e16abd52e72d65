// The contact sensor with libgazebo_ros_bumper in the simulation, around its core (bumper.h).
#ifndef TIANRACER_SIM_PLUGINS_BUMPER_SIM_BUMPER_H
#define TIANRACER_SIM_PLUGINS_BUMPER_SIM_BUMPER_H

#include <string>
#include <vector>

#include "tianracer_sim/plugins/bumper/bumper.h"
#include "tianracer_sim/plugins/sim_sensor.h"

namespace tianracer_sim {

/// contact sensor with libgazebo_ros_bumper: the link's touching pairs in the output frame.
class SimBumper : public SimCoreSensor<BumperConfig, std::vector<BumperState>> {
 public:
  static constexpr SensorOutputs kStates = kOutput;
  SimBumper(const SimSensorSetup& setup, BumperConfig config);
  /// The frame the states are in: world (or map) or a link with its tf_prefix.
  const std::string& frame() const { return frame_id_; }
  const std::vector<BumperState>& states() const { return output(); }

  void sample(SensorOutputs outputs, SensorWorld& world) override;

 private:
  std::string frame_link_, frame_id_;
  std::vector<LinkContact> contacts_;
  std::vector<BumperState> states_;
};

struct SensorKind;
/// The kind(s) of this folder, registered beside their classes (plugins/sensor_registry.h).
const SensorKind& bumperKind();

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_BUMPER_SIM_BUMPER_H
