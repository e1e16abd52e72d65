// The gazebo_ros plugins that turn a <sensor type="ray"> grid into something other than a
// LaserScan: libgazebo_ros_range (sensor_msgs/Range: the nearest of the beams) and
// libgazebo_ros_block_laser (sensor_msgs/PointCloud over the horizontal x vertical grid).
// Their configurations, parsed and validated, and the maths on Gazebo's shape ranges
// (shapeRanges(), ray_sensor.h). ROS-free: the messages are built in ros/laser_msgs.h.
#ifndef TIANRACER_SIM_PLUGINS_RAY_RAY_PLUGINS_H
#define TIANRACER_SIM_PLUGINS_RAY_RAY_PLUGINS_H

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "tianracer_sim/plugins/ray/ray_sensor.h"

namespace tianracer_sim {

/// sensor_msgs/Range's radiation_type values.
enum class Radiation : std::uint8_t { kUltrasound = 0, kInfrared = 1 };

/// libgazebo_ros_range on a ray sensor (gazebo_plugins/src/gazebo_ros_range.cpp).
struct RangeConfig {
  RaySensorConfig ray;          // the grid, range limits, pose and sensor rate
  std::string robot_namespace;  // <robotNamespace>: topics live under it ("" = "/")
  std::string topic_name = "/range";  // <topicName>, gazebo_ros_range's default
  std::string frame_name;       // <frameName>; default the link (gazebo_ros_range: "/world")
  Radiation radiation = Radiation::kUltrasound;  // <radiation>: "ultrasound" or "infrared"
  /// <fov> when given (as gazebo_ros_range); otherwise the grid's horizontal span
  /// max_angle - min_angle (gazebo_ros_range says 0.05).
  double fov = 0.0;
  double gaussian_noise = 0.0;  // <gaussianNoise>, m (stddev)
  double update_rate = 0.0;     // <updateRate>; 0 = the sensor rate
  std::uint64_t seed = 0;       // noise seed (set by the simulator)

  /// The rate a Range goes out at: the sensor's, throttled by updateRate when that is lower
  /// (gazebo_ros_range publishes from the sensor's updates when updateRate's period has run).
  double publishRate() const;
};

/// Reads a ray sensor with a libgazebo_ros_range plugin. Throws SensorError naming the sensor,
/// the element and the value (a number that is not one, negative noise, rate or fov, fov
/// beyond 2 pi). An unknown <radiation> is infrared, as gazebo_ros_range, with a warning.
RangeConfig parseRangeConfig(const SensorSpec& spec, const WarningSink& warn = {});
/// <robotNamespace>/<topicName>: sensor_msgs/Range at publishRate().
std::vector<SensorTopic> publishedTopics(const RangeConfig& config);

/// One sensor_msgs/Range's values.
struct RangeReading {
  float range = 0.0f;
  float min_range = 0.0f, max_range = 0.0f;
  float field_of_view = 0.0f;
  Radiation radiation = Radiation::kUltrasound;
};

/// gazebo_ros_range's PutRangeData on Gazebo's shape ranges (range_max where nothing is hit):
/// range = the smallest of them; when it is below max_range, range + N(0, gaussianNoise)
/// capped at range_max (no lower clip, as upstream). Noise from `rng` only then.
RangeReading rangeReading(const RangeConfig& config, const std::vector<float>& shape_ranges,
                          std::mt19937_64& rng);

/// libgazebo_ros_block_laser on a ray sensor (gazebo_plugins/src/gazebo_ros_block_laser.cpp).
struct BlockLaserConfig {
  RaySensorConfig ray;
  std::string robot_namespace;
  std::string topic_name = "/world";  // gazebo_ros_block_laser's default
  std::string frame_name;             // default the link (gazebo_ros_block_laser: "/world")
  double gaussian_noise = 0.0;        // <gaussianNoise>: on x, y, z and intensity
  double hokuyo_min_intensity = 101;  // <hokuyoMinIntensity>: read, unused (as upstream)
  double update_rate = 0.0;           // <updateRate>: read, unused (as upstream: sensor rate)
  std::uint64_t seed = 0;
  /// Points a cloud has: rangeCount x verticalRangeCount, Gazebo's samples * resolution
  /// (truncated), at least 1 each.
  int columns() const;
  int rows() const;
};

BlockLaserConfig parseBlockLaserConfig(const SensorSpec& spec, const WarningSink& warn = {});
/// <robotNamespace>/<topicName>: sensor_msgs/PointCloud at the sensor rate.
std::vector<SensorTopic> publishedTopics(const BlockLaserConfig& config);

/// A sensor_msgs/PointCloud's points (sensor frame) and its one channel (intensity).
struct BlockCloud {
  std::vector<float> xyz;        // x0 y0 z0 x1 ... rows() * columns() points, row by row
  std::vector<float> intensity;  // one per point
};

/// gazebo_ros_block_laser's PutLaserData on Gazebo's shape ranges, into `out` (reused):
/// point (i, j) interpolates the four rays around hb = i (rays-1)/(columns-1) and
/// vb = j (rings-1)/(rows-1) bilinearly; r < range_min -> -inf, r > range_max -> +inf
/// (REP 117); it is placed at yaw = (hja + hjb)/2 * yDiff/(rays-1) + min_angle and pitch
/// likewise (with one ray per step, half a step past the ray whose range it carries, as
/// upstream): (r cos p cos y, r cos p sin y, r sin p); x, y and z each get N(0, gaussianNoise)
/// unless |range_max - r| <= 1e-6; intensity is the mean of the four rays' laser_retro (0
/// here) plus N(0, gaussianNoise). Draws in that order, from `rng`.
void blockLaserCloud(const BlockLaserConfig& config, const std::vector<float>& shape_ranges,
                     std::mt19937_64& rng, BlockCloud* out);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_RAY_RAY_PLUGINS_H
