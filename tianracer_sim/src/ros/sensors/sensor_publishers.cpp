// The one table pairing each SensorKind (sensors/sensor_registry.cpp) with its publisher.
#include <map>
#include <stdexcept>

#include "factories.h"

namespace tianracer_sim {

std::unique_ptr<SensorListener> makeSensorPublisher(SimSensor& sensor, const PublisherSetup& setup) {
  using Factory = std::unique_ptr<SensorListener> (*)(SimSensor&, const PublisherSetup&);
  static const std::map<std::string, Factory> factories = {
      {"lidar", &makeLidarPublisher},
      {"camera", &makeCameraPublisher},
      {"multicamera", &makeMultiCameraPublisher},
      {"depth_camera", &makeDepthCameraPublisher},
      {"imu", &makeImuPublisher},
      {"imu_plugin", &makeImuPublisher},
      {"p3d", &makeP3dPublisher},
      {"bumper", &makeBumperPublisher},
      {"range", &makeRangePublisher},
      {"block_laser", &makeBlockLaserPublisher},
      {"drive", &makeDrivePublisher},
      {"hector_imu", &makeHectorImuPublisher},
      {"hector_gps", &makeHectorGpsPublisher},
      {"hector_magnetic", &makeHectorMagneticPublisher},
      {"hector_sonar", &makeHectorSonarPublisher},
  };
  const auto it = factories.find(sensor.kind());
  if (it == factories.end())
    throw std::logic_error("sensor kind '" + sensor.kind() + "' has no publisher registered");
  return it->second(sensor, setup);
}

}  // namespace tianracer_sim
