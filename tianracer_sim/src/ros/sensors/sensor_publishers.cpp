// The one table pairing each SensorKind (sensors/sensor_registry.cpp) with its publisher.
#include <map>
#include <stdexcept>

#include "factories.h"

namespace tianracer_sim {

bool Schedule::due(double t) {
  if (t + 1e-9 < next) return false;
  if (period <= 0.0) {
    next = t;
    return true;
  }
  // Keep the nominal grid (a 30 Hz camera on 1 ms steps fires at 34, 67, 100 ms: 30 Hz on
  // average); only when more than a period behind (a pause, a reset) restart from now, so
  // that nothing bursts to catch up.
  next += period;
  if (next <= t) next = t + period;
  return true;
}

std::unique_ptr<SensorPublisher> makeSensorPublisher(const SensorKind& kind,
                                                     const SensorSetup& setup) {
  using Factory = std::unique_ptr<SensorPublisher> (*)(const SensorSetup&);
  static const std::map<std::string, Factory> factories = {
      {"lidar", &makeLidarPublisher},
      {"camera", &makeCameraPublisher},
      {"multicamera", &makeMultiCameraPublisher},
      {"depth_camera", &makeDepthCameraPublisher},
      {"imu", &makeImuPublisher},
      {"imu_plugin", &makeImuPluginPublisher},
      {"p3d", &makeP3dPublisher},
      {"bumper", &makeBumperPublisher},
  };
  const auto it = factories.find(kind.id);
  if (it == factories.end())
    throw std::logic_error("sensor kind '" + kind.id + "' has no publisher registered");
  return it->second(setup);
}

}  // namespace tianracer_sim
