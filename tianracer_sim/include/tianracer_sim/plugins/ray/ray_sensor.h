// A Gazebo <sensor type="ray"> with its libgazebo_ros_laser plugin, as a plain validated struct,
// and a RaySensor that scans a Scene with it (docs/model_and_sensors.md). ROS-free.
#ifndef TIANRACER_SIM_PLUGINS_RAY_RAY_SENSOR_H
#define TIANRACER_SIM_PLUGINS_RAY_RAY_SENSOR_H

#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/model/robot_model.h"  // SensorSpec, SensorError, WarningSink
#include "tianracer_sim/plugins/sensor_topics.h"

namespace tianracer_sim {

/// <ray><noise>: type "gaussian" (SDF's default) or "none".
struct RayNoise {
  std::string type = "none";
  double mean = 0.0;
  double stddev = 0.0;
  bool enabled() const { return type == "gaussian"; }
};

struct RaySensorConfig {
  std::string name;  // <sensor name>
  std::string link;  // the link it is attached to
  Eigen::Isometry3d X_LS = Eigen::Isometry3d::Identity();  // sensor in link
  double update_rate = 0.0;                                // Hz; 0 = every step (Gazebo)
  // <ray><scan><horizontal>; SDF defaults.
  int samples = 640;
  double resolution = 1.0;  // parsed and validated; rays cast = samples (see the .cpp)
  double min_angle = 0.0;
  double max_angle = 0.0;
  // <ray><scan><vertical>: more than one sample makes a 3D lidar (a velodyne cloud).
  int vertical_samples = 1;  // 1..kMaxVerticalSamples
  double vertical_resolution = 1.0;
  double vertical_min_angle = 0.0;
  double vertical_max_angle = 0.0;
  // <ray><range>
  double range_min = 0.0;
  double range_max = 0.0;
  double range_resolution = 0.0;  // parsed; not applied to ranges, as in Gazebo's RaySensor
  RayNoise noise;
  // libgazebo_ros_laser (or _gpu_laser) parameters, with that plugin's defaults except the frame.
  bool has_ros_plugin = false;
  /// libgazebo_ros_velodyne_laser / _gpu_laser (velodyne_gazebo_plugins): a PointCloud2 of the
  /// points with max(min_range, <range><min>) < r < min(max_range, <range><max>), r with
  /// gaussianNoise; fields x y z intensity ring (PCL's PointXYZIR layout, 32 bytes a point).
  bool velodyne = false;
  double cloud_min_range = 0.0;  // velodyne min_range
  double cloud_max_range = std::numeric_limits<double>::infinity();  // velodyne max_range
  double cloud_noise = 0.0;      // velodyne gaussianNoise (m)
  std::string topic_name = "/world";  // gazebo_ros_laser's default
  std::string frame_name;             // default: the link name (gazebo_ros_laser says "/world")
  std::string robot_namespace;        // "" unless given
  /// gazebo_ros_laser / gpu_laser with <robotNamespace/> given but empty: GetRobotNamespace
  /// (gazebo_ros_utils.h) makes it the model's name (set where the model is known).
  bool namespace_from_model = false;
  /// Noise seed (not in SDF: set by the node, e.g. from a ~seed parameter).
  std::uint64_t seed = 0;

  /// angle_increment = (max_angle - min_angle) / (samples - 1); 0 for a single sample.
  double angleIncrement() const {
    return samples > 1 ? (max_angle - min_angle) / (samples - 1) : 0.0;
  }
  /// Beam i points at min_angle + i * angleIncrement() about the sensor's z axis.
  double angle(int i) const { return min_angle + i * angleIncrement(); }
  /// Ring j is at vertical_min_angle + j * (max - min) / (vertical_samples - 1) of elevation
  /// (0 for a planar lidar).
  double verticalAngle(int j) const {
    return vertical_samples > 1
               ? vertical_min_angle +
                     j * (vertical_max_angle - vertical_min_angle) / (vertical_samples - 1)
               : 0.0;
  }
  int rayCount() const { return samples * vertical_samples; }
};

/// More rings are refused (Gazebo accepts any; no real lidar has more than a few hundred).
constexpr int kMaxVerticalSamples = 512;

/// Reads a SensorSpec of type "ray" (its pose, rate and plugins as parsed by the model loader;
/// <ray> from its raw XML). Unknown elements and plugin parameters are warned once each.
/// Throws SensorError (wrong type, unparsable or invalid values; see validate()).
RaySensorConfig parseRaySensorConfig(const SensorSpec& spec, const WarningSink& warn = {});

/// Throws SensorError naming the sensor and the value when: any number is not finite,
/// samples <= 0, vertical samples outside 1..kMaxVerticalSamples, vertical min > max, resolution <= 0, min_angle > max_angle, range_min < 0, range_min >= range_max,
/// range_resolution < 0, update_rate < 0, noise stddev < 0, or the noise type is unknown.
void validate(const RaySensorConfig& config);

/// What gazebo_ros_laser publishes: sensor_msgs/LaserScan on <robotNamespace>/<topicName> at
/// the sensor rate; with a velodyne plugin, sensor_msgs/PointCloud2 there.
std::vector<SensorTopic> publishedTopics(const RaySensorConfig& config);

class RayCaster;
struct Scene;

/// Applies the range model to true ranges (distances from the sensor origin, +inf for no hit):
///   r >= range_max -> +inf;  r <= range_min -> -inf (REP 117, as Gazebo's RaySensor; rays
///   cast from range_min reach that only for a surface at range_min);
///   else r + N(mean, stddev) clamped to [range_min, range_max] (noise enabled), r otherwise.
/// Noise is drawn only for in-range beams, in beam order, from `rng`.
void applyRangeModel(const RaySensorConfig& config, std::mt19937_64& rng, float* ranges, int n);

/// The 3D lidar's range model (velodyne_gazebo_plugins): r plus SDF <noise> and the plugin's
/// gaussianNoise (both drawn only for hits), kept when
/// max(cloud_min_range, range_min) < r < min(cloud_max_range, range_max), NaN otherwise.
void applyCloudRangeModel(const RaySensorConfig& config, std::mt19937_64& rng, float* ranges,
                          int n);

/// Reused buffers of a scan: beam directions in the sensor frame (recomputed only when the
/// beam layout changes) and in the world frame.
struct RayScanBuffers {
  std::vector<Eigen::Vector3d> dirs_S;
  double dirs_min = 0.0, dirs_inc = 0.0, dirs_vmin = 0.0, dirs_vmax = 0.0;
  int dirs_rings = 0;
  std::vector<Eigen::Vector3f> dirs_W;
};

/// One scan from the sensor pose X_WS: ray (j, i) at index j * samples + i along
/// (cos p_j cos a_i, cos p_j sin a_i, sin p_j) in the sensor frame, a_i = config.angle(i),
/// p_j = config.verticalAngle(j) (a planar lidar: j = 0, p = 0), true ranges from the caster
/// over [range_min, range_max] as in Gazebo (what lies nearer than range_min is not seen,
/// every body beyond it is, the sensor's own included; ranges are distances from the sensor
/// origin; moving bodies updated first), then applyRangeModel() (applyCloudRangeModel() for a
/// velodyne) with noise from `rng`. `ranges` is resized to rayCount(); no allocation once warm.
void scanRays(RayCaster& caster, const Scene& scene, const Eigen::Isometry3d& X_WS,
              const RaySensorConfig& config, std::mt19937_64& rng, RayScanBuffers* buffers,
              std::vector<float>* ranges);
/// The rays of scanRays() cast, without any range model: distances from the sensor origin to
/// the first surface in [range_min, range_max], +inf for none. `ranges` is resized.
void castRayGrid(RayCaster& caster, const Scene& scene, const Eigen::Isometry3d& X_WS,
                 const RaySensorConfig& config, RayScanBuffers* buffers,
                 std::vector<float>* ranges);
/// What gazebo_ros's ray plugins (range, block laser) read: Gazebo's LaserShape()->GetRange(i)
/// (gazebo/physics/MultiRayShape.cc), the ray grid cast over [range_min, range_max] with
/// range_max for a ray that hits nothing; no noise (<ray><noise> is applied by Gazebo's
/// RaySensor to its LaserScan, not to the shape's ranges).
void shapeRanges(const RaySensorConfig& config, RayCaster& caster, const Scene& scene,
                 const Eigen::Isometry3d& X_WS, RayScanBuffers* buffers,
                 std::vector<float>* ranges);
/// As above with buffers of its own (allocates; for tests and tools).
std::vector<float> scanRays(RayCaster& caster, const Scene& scene, const Eigen::Isometry3d& X_WS,
                            const RaySensorConfig& config, std::mt19937_64& rng);

/// A configured ray sensor with its own noise generator (std::mt19937_64 seeded with
/// config.seed): the same seed and the same scenes give identical scans.
class RaySensor {
 public:
  /// Validates the config (throws SensorError).
  explicit RaySensor(RaySensorConfig config);

  const RaySensorConfig& config() const { return config_; }
  void reseed(std::uint64_t seed) { rng_.seed(seed); }

  /// One scan from X_WS = X_WL * X_LS (X_WL: the pose of the sensor's link in the world).
  /// The returned buffer is reused by the next call (no allocation once warm).
  const std::vector<float>& scan(RayCaster& caster, const Scene& scene,
                                 const Eigen::Isometry3d& X_WL);
  /// Unit ray directions in the sensor frame, in range order (valid after a scan).
  const std::vector<Eigen::Vector3d>& directions() const { return buffers_.dirs_S; }

 private:
  RaySensorConfig config_;
  std::mt19937_64 rng_;
  RayScanBuffers buffers_;
  std::vector<float> ranges_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_RAY_RAY_SENSOR_H
