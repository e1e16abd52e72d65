// SensorHost: the sensors and sensor-like Gazebo plugins of the simulation's models, and the
// camera frames they render, as Gazebo's sensors::SensorManager runs its sensors and the
// rendering thread draws them (gazebo/sensors/SensorManager.cc). It makes each one from its
// spec through the sensor registry (plugins/sensor_registry.h), runs the due ones every step
// (update, sample, hand their outputs to their listeners), and renders the due frames on the
// frame worker from a snapshot of the step's scene. The Simulator says which model a sensor
// belongs to and is the SensorWorld the sensors read. ROS-free.
#ifndef TIANRACER_SIM_SIMULATOR_SENSOR_HOST_H
#define TIANRACER_SIM_SIMULATOR_SENSOR_HOST_H

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tianracer_sim/common/step_profile.h"
#include "tianracer_sim/render/renderer.h"
#include "tianracer_sim/scene/scene.h"
#include "tianracer_sim/plugins/sim_sensor.h"
#include "tianracer_sim/sim/frame_worker.h"

namespace tianracer_sim {

struct SimulatorLog;

class SensorHost {
 public:
  /// `scene` is what cameras draw; `update_scene` brings its poses to the current step before a
  /// frame's snapshot. `log` and `profile` outlive the host.
  SensorHost(SensorWorld& world, const Scene& scene, std::function<void()> update_scene,
             const SimulatorLog& log, StepProfile* profile);
  ~SensorHost();  // the frame in flight finishes while its sensors still exist
  SensorHost(const SensorHost&) = delete;
  SensorHost& operator=(const SensorHost&) = delete;

  /// Makes the sensor `setup.spec` names (its kind from the registry; setup's index, renderer
  /// and world are filled here), attaches it (`attach`, may throw) and runs it from the next
  /// sense(). "" when it is set up or has nothing to produce; otherwise why it is left out
  /// (its spec's error, a type not simulated, or what its set-up threw), also logged with
  /// `owner` ("robot 'x'" or "model 'x'").
  std::string add(SimSensorSetup setup, const std::string& owner,
                  const std::function<void(SimSensor&)>& attach);
  /// Attaches each sensor of model `id` (made by add() without an attach) through `attach`;
  /// one that throws is logged with `owner`, left out and taken away. Returns {sensor name:
  /// why} for those left out.
  std::map<std::string, std::string> attachModel(ModelId id, const std::string& owner,
                                                 const std::function<void(SimSensor&)>& attach);
  /// Takes the sensors of model `id` out (after the frame in flight).
  void removeModel(ModelId id);
  /// The sensor called `name` on model `id` (model plugins by their plugin name); nullptr if none.
  SimSensor* find(ModelId id, const std::string& name) const;
  /// Every sensor, in set-up order.
  const std::vector<std::unique_ptr<SimSensor>>& sensors() const { return sensors_; }

  /// The sensors due at time t: updated, sampled when wanted, handed to their listeners; the
  /// frames they requested go to the frame worker.
  void sense(double t);
  /// A camera's frame, to render after this step's sense().
  void requestFrame(const FrameRequest& request) { due_frames_.push_back(request); }
  /// Waits for the frame in flight: rendered outputs are complete afterwards.
  void waitFrames();
  /// Sensors' schedules and histories from time t (reset_simulation).
  void restart(double t);

 private:
  Renderer* ensureRenderer();
  void submitFrames(double t);

  struct FrameJob {
    double t = 0.0;
    std::vector<FrameRequest> frames;
  };

  SensorWorld& world_;
  const Scene& scene_;
  std::function<void()> update_scene_;
  const SimulatorLog& log_;
  StepProfile* profile_ = nullptr;
  int frame_wait_row_ = -1, frames_row_ = -1;

  std::unique_ptr<Renderer> renderer_;
  bool renderer_failed_ = false;
  // After renderer_: camera sensors render through it and go first.
  std::vector<std::unique_ptr<SimSensor>> sensors_;
  std::map<std::string, int> sensors_of_kind_;  // SensorKind id -> sensors set up
  std::vector<FrameRequest> due_frames_;        // filled each step, handed to the worker
  Scene render_scene_;                          // the worker's snapshot of scene_
  // Started with the first frame; reset first in ~SensorHost (it uses the sensors above).
  std::unique_ptr<FrameWorker<FrameJob>> frame_worker_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIMULATOR_SENSOR_HOST_H
