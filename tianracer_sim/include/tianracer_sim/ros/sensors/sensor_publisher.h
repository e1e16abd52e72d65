// The node side of the sensor seam: one SensorPublisher per simulated sensor, made by the
// factory registered for its SensorKind (sensors/sensor_registry.h). The node loops over its
// publishers every step and knows no sensor type; a publisher owns its ROS-free core sensor,
// its schedule, publishers and messages.
#ifndef TIANRACER_SIM_ROS_SENSORS_SENSOR_PUBLISHER_H
#define TIANRACER_SIM_ROS_SENSORS_SENSOR_PUBLISHER_H

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include <Eigen/Geometry>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/sensors/bumper.h"  // BumperContact
#include "tianracer_sim/sensors/p3d.h"  // LinkState
#include "tianracer_sim/sensors/sensor_registry.h"

namespace tianracer_sim {

/// Something published on a sim-time schedule: due when time >= next; next advances by
/// period (a reset restarts it; a long pause does not cause a burst).
struct Schedule {
  double period = 0.0;  // s; 0 = every step
  double next = 0.0;
  bool due(double t);
  void restart(double t) { next = t; }
};

/// Published messages per sensor since the last status report, against the target rate.
struct SensorStat {
  std::string name;  // e.g. "/scan"
  double target = 0.0;
  std::uint64_t count = 0;
  std::uint64_t skipped = 0;  // due while nobody subscribed (nothing rendered)
  std::uint64_t renders = 0;  // frames rendered / scans cast in total
};

class SensorPublisher;

/// A frame rendered off the step thread: the sensor, its link's pose at the step and the
/// outputs wanted (a bit mask whose meaning is the sensor's).
struct FrameRequest {
  SensorPublisher* sensor = nullptr;
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  unsigned outputs = 0;
};

/// What a publisher needs from the node at a step.
class SensorHost {
 public:
  virtual ~SensorHost() = default;
  /// The scene at this step (robot bodies brought to the physics poses on first use).
  virtual const Scene& scene() = 0;
  virtual RayCaster& caster() = 0;
  /// Pose in the world of link `link` of robot `robot` at this step.
  virtual Eigen::Isometry3d linkPose(std::size_t robot, const std::string& link) const = 0;
  /// Pose and world-frame velocities of a link, exact when the link is rigid with the robot's
  /// root body (the base's twist carried to the link's origin); false otherwise (the caller
  /// differentiates poses).
  virtual bool linkState(std::size_t robot, const std::string& link, LinkState* state) const = 0;
  /// Renders the frame on the frame worker from a snapshot of this step's scene, then
  /// calls request.sensor->renderFrame() there.
  virtual void requestFrame(const FrameRequest& request) = 0;
  /// The contacts of the body that carries `link` in the last step (a wheel on the ground is
  /// not one), named "model::link".
  virtual void linkContacts(std::size_t robot, const std::string& link,
                            std::vector<BumperContact>* out) = 0;
  virtual SensorStat& stat(std::size_t index) = 0;
};

/// Everything a factory needs to set a sensor up.
struct SensorSetup {
  const SensorSpec* spec = nullptr;
  std::size_t robot = 0;  // the node's robot index (for SensorHost::linkPose)
  std::string robot_name;     // also Gazebo's default namespace of some plugins
  std::string tf_prefix;      // "" or e.g. "tianracer_02"
  int own_body = -1;          // scene body of the sensor's link
  std::uint64_t seed = 0;     // the node's ~seed
  int index = 0;              // sensors of this kind set up before this one
  Eigen::Vector3d gravity{0.0, 0.0, -9.8};  // the world's, m/s^2
  double dt = 0.001;          // the physics step, s
  ros::NodeHandle root;       // "/" on the node's callback queue
  tf2_ros::StaticTransformBroadcaster* static_tf = nullptr;
  WarningSink warn;
  /// Throws for a link the robot does not have.
  std::function<void(const std::string& link)> check_link;
  /// Throws when another sensor already publishes `topic`.
  std::function<void(const std::string& topic, const std::string& owner)> claim_topic;
  /// The shared offscreen renderer; nullptr when there is none (reported once by the node).
  std::function<Renderer*()> renderer;
  /// Registers a status line entry; returns its index for SensorHost::stat().
  std::function<std::size_t(const std::string& name, double target_hz)> add_stat;
};

class SensorPublisher {
 public:
  virtual ~SensorPublisher() = default;
  /// On the step thread, every step: publish what is due at sim time t (or request frames).
  /// Must not allocate once warm.
  virtual void step(double t, const ros::Time& stamp, SensorHost& host) = 0;
  /// On the frame worker's thread: render `request` from `scene` and publish it.
  virtual void renderFrame(const Scene& /*scene*/, const FrameRequest& /*request*/,
                           const ros::Time& /*stamp*/) {}
  /// Restarts the schedules at sim time t (reset_simulation).
  virtual void restart(double t) = 0;
};

/// Makes the publisher registered for `kind` (nullptr when the sensor publishes nothing, e.g.
/// a camera without a gazebo_ros plugin: the factory says why through setup.warn). Throws
/// std::exception naming the sensor on bad input. The factories are listed in one table,
/// src/ros/sensors/sensor_publishers.cpp.
std::unique_ptr<SensorPublisher> makeSensorPublisher(const SensorKind& kind,
                                                     const SensorSetup& setup);

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ROS_SENSORS_SENSOR_PUBLISHER_H
