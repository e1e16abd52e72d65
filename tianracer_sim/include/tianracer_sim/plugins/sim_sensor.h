// The simulator's side of a sensor: one SimSensor per simulated sensor, owned by the Simulator,
// made by its kind (plugins/<kind>/sim_<kind>.h) from a SimSensorSetup,
// holding its ROS-free core (ray sensor, camera, IMU, ...), its schedules, its latest output and
// its counts. What consumes the output (the ROS node's publisher of the sensor, a Python
// environment) is a SensorListener: it says which due outputs it wants, so that nothing is
// cast or rendered for nobody, and it is told when they are ready.
//
// At each step (Simulator::sense()), in set-up order, for each sensor:
//   due = update(t)                 motion history every step; which outputs are due now
//   want = listener.wanted(due)     (no listener: everything due)
//   sample(want) or skip()          cast / measure now, or request a frame (rendered on the
//                                   frame worker from a snapshot of this step's scene)
//   listener.onOutputs(...)         at the step for measured outputs, on the frame worker's
//                                   thread for rendered ones
#ifndef TIANRACER_SIM_PLUGINS_SIM_SENSOR_H
#define TIANRACER_SIM_PLUGINS_SIM_SENSOR_H

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "tianracer_sim/common/warning.h"
#include "tianracer_sim/lidar/ray_caster.h"
#include "tianracer_sim/model/robot_model.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/plugins/link_data.h"
#include "tianracer_sim/common/schedule.h"

namespace urdf {
class ModelInterface;
}

namespace tianracer_sim {

class Renderer;

/// A model of the simulation (a robot or a world model), by an id that is never reused.
using ModelId = int;
constexpr ModelId kNoModel = -1;

/// A link of a model: where a sensor sits and what it reads. Robots and world models alike.
struct LinkRef {
  ModelId model = kNoModel;
  std::string link;
};

/// Bits naming a sensor's outputs; what each bit means is the sensor kind's (SimCamera::kImage...).
using SensorOutputs = std::uint64_t;

class SimSensor;

/// A frame to render off the step thread: the sensor, its link's pose at the step and the
/// outputs wanted.
struct FrameRequest {
  SimSensor* sensor = nullptr;
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  SensorOutputs outputs = 0;
};

/// What a sensor reads from the simulation at a step: general questions about links and the
/// scene, nothing specific to a sensor kind.
class SensorWorld {
 public:
  virtual ~SensorWorld() = default;
  /// The physics step and the gravity now in force (s, m/s^2): set_physics_properties may
  /// change them between steps.
  virtual double dt() const = 0;
  virtual Eigen::Vector3d gravity() const = 0;
  /// The scene at this step (bodies brought to the physics poses on first use).
  virtual const Scene& scene() = 0;
  virtual RayCaster& caster() = 0;
  /// Pose of the link in the world at this step.
  virtual Eigen::Isometry3d linkPose(const LinkRef& link) const = 0;
  /// Pose and world-frame velocities of the link, when the physics knows them exactly (a link
  /// rigid with its model's root body); false otherwise (the caller differentiates poses).
  virtual bool linkState(const LinkRef& link, LinkState* state) const = 0;
  /// The contacts in the last step of the body that carries the link (a wheel on the ground
  /// is not one), own named "model::link". Cleared first.
  virtual void linkContacts(const LinkRef& link, std::vector<LinkContact>* out) = 0;
  /// Renders the frame on the frame worker from a snapshot of this step's scene
  /// (request.sensor->render()), then hands it to the sensor's listener there.
  virtual void requestFrame(const FrameRequest& request) = 0;

  // What model plugins that drive a model (plugins/drives/drives.h) read and command.
  /// The model's movable joint `joint`: its index for the calls below, and the links it joins
  /// (parent, child; may be null); -1 when the model has no movable joint of that name (a
  /// static model has none).
  virtual int jointIndex(ModelId model, const std::string& joint, std::string* parent_link,
                         std::string* child_link) const = 0;
  virtual double jointPosition(ModelId model, int joint) const = 0;
  virtual double jointVelocity(ModelId model, int joint) const = 0;
  /// A velocity motor on the joint: its rate driven to omega with at most max_effort (N m or
  /// N), as Gazebo's Joint::SetParam("vel") with "fmax"; it holds until replaced.
  virtual void setJointVelocity(ModelId model, int joint, double omega, double max_effort) = 0;
  /// The model frame's pose and world-frame velocities (a static model: its pose, at rest).
  virtual LinkState modelFrameState(ModelId model) const = 0;
  /// Gazebo's Model::SetLinearVel / SetAngularVel (world frame, the model frame's origin).
  /// False for a model that does not move (static).
  virtual bool setModelVelocity(ModelId model, const Eigen::Vector3d& linear_W,
                                const Eigen::Vector3d& angular_W) = 0;
};

/// The consumer of a sensor's outputs.
class SensorListener {
 public:
  virtual ~SensorListener() = default;
  /// Of the outputs due now, those someone wants; the others are not computed.
  virtual SensorOutputs wanted(const SimSensor& sensor, SensorOutputs due) = 0;
  /// `outputs` are ready for sim time t: called on the stepping thread for measured outputs,
  /// on the frame worker's thread for rendered ones (SimSensor::rendered()).
  virtual void onOutputs(const SimSensor& sensor, SensorOutputs outputs, double t) = 0;
};

/// The period of a rate for a Schedule: 1/rate, 0 (every step) for a rate of 0.
inline double periodOf(double rate) { return rate > 0.0 ? 1.0 / rate : 0.0; }

class SimSensor {
 public:
  SimSensor(std::string kind, std::string name, LinkRef link, std::string model_name)
      : kind_(std::move(kind)), name_(std::move(name)), link_(std::move(link)),
        model_name_(std::move(model_name)) {}
  virtual ~SimSensor() = default;
  SimSensor(const SimSensor&) = delete;
  SimSensor& operator=(const SimSensor&) = delete;

  /// The SensorKind id (plugins/sensor_registry.h), e.g. "lidar".
  const std::string& kind() const { return kind_; }
  const std::string& name() const { return name_; }
  const LinkRef& link() const { return link_; }
  const std::string& modelName() const { return model_name_; }

  /// Every step, after the physics: keeps what the sensor differentiates, advances the
  /// schedules, returns the outputs due at sim time t.
  virtual SensorOutputs update(double t, SensorWorld& world) = 0;
  /// Computes `outputs` (a subset of the due ones, not empty): measured now, or a frame
  /// requested (world.requestFrame()).
  virtual void sample(SensorOutputs outputs, SensorWorld& world) = 0;
  /// Due outputs that nobody wanted.
  virtual void skip() {}
  /// On the frame worker: renders a requested frame from `scene`.
  virtual void render(const Scene& /*scene*/, const FrameRequest& /*request*/) {}
  /// The outputs that render() produces (delivered from the frame worker).
  virtual SensorOutputs rendered() const { return 0; }
  /// The outputs whose samples the status counts: the rendered ones of a sensor that renders
  /// (a camera's image, not its camera_info), else all.
  virtual SensorOutputs counted() const {
    const SensorOutputs r = rendered();
    return r ? r : ~SensorOutputs(0);
  }
  /// Time went back (reset_simulation): schedules restart at t, histories are forgotten.
  virtual void restart(double t) = 0;

  SensorListener* listener() const { return listener_.get(); }
  void setListener(std::unique_ptr<SensorListener> listener) { listener_ = std::move(listener); }
  SensorStat& stat() { return stat_; }
  const SensorStat& stat() const { return stat_; }

  /// Its rows in the step profile (common/step_profile.h), by its kind; -1 when not profiled.
  struct ProfileRows {
    int update = -1, sample = -1, publish = -1;  // the stepping thread
    int render = -1, frame_publish = -1;         // the frame worker
  };
  const ProfileRows& profileRows() const { return profile_rows_; }
  void setProfileRows(const ProfileRows& rows) { profile_rows_ = rows; }

 protected:
  /// Samples on `schedule` at `rate` (Hz; 0 = every step); the status counts it as `name`
  /// against that rate.
  void sampleAt(Schedule& schedule, const std::string& name, double rate) {
    schedule.period = periodOf(rate);
    stat_.name = name;
    stat_.target = rate;
  }

 private:
  std::string kind_, name_;
  LinkRef link_;
  std::string model_name_;
  std::unique_ptr<SensorListener> listener_;
  SensorStat stat_;
  ProfileRows profile_rows_;
};

/// Everything a sensor kind needs to set a sensor up.
struct SimSensorSetup {
  const SensorSpec* spec = nullptr;
  ModelId model = kNoModel;
  std::string model_name;     // also Gazebo's default namespace of some plugins
  std::string tf_prefix;      // "" or e.g. "tianracer_02": prefixes the frames of its outputs
  std::uint64_t seed = 0;     // the simulation's seed
  int index = 0;              // sensors of this kind set up before this one
  Eigen::Vector3d gravity{0.0, 0.0, -9.8};  // the world's, m/s^2
  /// A robot's URDF (world models: null): a camera whose frameName is an optical link of it
  /// stamps its images there (plugins/camera/optical_frame.h).
  const urdf::ModelInterface* urdf = nullptr;
  WarningSink warn;
  /// Throws for a link the model does not have.
  std::function<void(const std::string& link)> check_link;
  /// The shared offscreen renderer; nullptr when there is none (reported once).
  std::function<Renderer*()> renderer;
  /// The simulation (model plugins that drive look their joints up in it); may be null.
  SensorWorld* world = nullptr;

  /// The link `name` of the sensor's model.
  LinkRef linkRef(const std::string& name) const { return LinkRef{model, name}; }
  /// Throws InputError placed at the sensor's element (its <sensor>, or a model plugin's
  /// <plugin>): "<file>:<line>: <message>".
  [[noreturn]] void fail(const std::string& message) const {
    throw InputError(SourceLocation{spec ? spec->source : "", spec ? spec->line : 0, "sensor"},
                     message);
  }
};

namespace sim_sensor_internal {
template <class T, class = void>
struct HasConfig : std::false_type {};
template <class T>
struct HasConfig<T, std::void_t<decltype(std::declval<const T&>().config())>> : std::true_type {};
}  // namespace sim_sensor_internal

/// The shape most kinds share: a ROS-free core (its config(), what it measures; or just the
/// config, for a kind whose measurement is a function of it) sampled on one schedule, with one
/// output whose latest value the publisher reads (an empty one before the first sample). A
/// kind supplies sample() and, where it differentiates poses, track() (every step) and
/// forget() (its histories, at a restart). SimLidar, SimImu, SimP3d, SimBumper and the ray
/// grids (SimRange, SimBlockLaser) are this. Not this: the cameras (several outputs, rendered
/// on the frame worker, two schedules or triggers), the drives (they act every step and have
/// three outputs), hector's plugins (their UpdateTimer's clock, whose tick gives the models'
/// dt and runs when nobody listens; the IMU and GPS have two outputs).
template <class Core, class Output>
class SimCoreSensor : public SimSensor {
 public:
  static constexpr SensorOutputs kOutput = 1;
  const auto& config() const {
    if constexpr (sim_sensor_internal::HasConfig<Core>::value) {
      return core_.config();
    } else {
      return core_;
    }
  }

  SensorOutputs update(double t, SensorWorld& world) override {
    track(t, world);
    return schedule_.due(t) ? kOutput : 0;
  }
  void restart(double t) override {
    schedule_.restart(t);
    forget();
  }

 protected:
  /// `core` is sampled at `rate` (Hz; 0: every step); the status counts it as `name`.
  SimCoreSensor(std::string kind, const SimSensorSetup& setup, const std::string& name,
                const std::string& link, Core core, double rate)
      : SimSensor(std::move(kind), name, setup.linkRef(link), setup.model_name),
        core_(std::move(core)) {
    sampleAt(schedule_, name, rate);
  }
  /// Every step before the schedule: the motion history a kind differentiates.
  virtual void track(double /*t*/, SensorWorld& /*world*/) {}
  /// At a restart: the histories forgotten.
  virtual void forget() {}
  /// The latest output (held by the core or the kind).
  const Output& output() const { return *output_; }
  void setOutput(const Output& output) { output_ = &output; }

  Core core_;

 private:
  Schedule schedule_;
  Output none_{};
  const Output* output_ = &none_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_PLUGINS_SIM_SENSOR_H
