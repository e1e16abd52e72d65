#include "tianracer_sim/simulator/sensor_host.h"

#include <algorithm>

#include "tianracer_sim/plugins/sensor_registry.h"
#include "tianracer_sim/simulator/simulator.h"  // SimulatorLog

namespace tianracer_sim {

SensorHost::SensorHost(SensorWorld& world, const Scene& scene, std::function<void()> update_scene,
                       const SimulatorLog& log, StepProfile* profile)
    : world_(world),
      scene_(scene),
      update_scene_(std::move(update_scene)),
      log_(log),
      profile_(profile),
      frame_wait_row_(profileRow(profile, "frames: waiting for the worker's last frame")),
      frames_row_(profileRow(profile, "frames: scene snapshot, hand-off to the worker")) {}

SensorHost::~SensorHost() { frame_worker_.reset(); }

std::string SensorHost::add(SimSensorSetup setup, const std::string& owner,
                            const std::function<void(SimSensor&)>& attach) {
  const SensorSpec& spec = *setup.spec;
  const std::string what = spec.type.empty() ? "plugin" : "sensor";
  if (!spec.error.empty()) {
    say(log_.error, owner + ": " + what + " '" + spec.name + "' left out: " + spec.error);
    return spec.error;
  }
  const SensorKind* kind = findSensorKind(spec);
  if (!kind) {
    say(log_.warn, owner + ": sensor '" + spec.name + "' of type '" + spec.type +
                       "' is not supported; left out");
    return "sensor type '" + spec.type + "' is not simulated";
  }
  setup.index = sensors_of_kind_[kind->id];
  setup.renderer = [this]() { return ensureRenderer(); };
  setup.world = &world_;
  // A bad sensor is reported and left out; the model and the other sensors run on.
  try {
    std::unique_ptr<SimSensor> sensor = kind->make(setup);
    if (!sensor) return "";
    if (profile_) {
      SimSensor::ProfileRows rows;
      rows.update = profile_->row("sensor " + kind->id + ": update");
      rows.sample = profile_->row("sensor " + kind->id + ": sample (cast, measure)");
      rows.publish = profile_->row("sensor " + kind->id + ": publish");
      rows.render = profile_->row("frame worker: " + kind->id + " render");
      rows.frame_publish = profile_->row("frame worker: " + kind->id + " publish");
      sensor->setProfileRows(rows);
    }
    if (attach) attach(*sensor);
    sensors_.push_back(std::move(sensor));
    ++sensors_of_kind_[kind->id];
    return "";
  } catch (const std::exception& e) {
    say(log_.error, owner + ": " + what + " '" + spec.name + "'" +
                        (spec.link.empty() ? "" : " on link '" + spec.link + "'") +
                        " left out: " + e.what());
    return e.what();
  }
}

std::map<std::string, std::string> SensorHost::attachModel(
    ModelId id, const std::string& owner, const std::function<void(SimSensor&)>& attach) {
  std::map<std::string, std::string> left_out;
  for (auto it = sensors_.begin(); it != sensors_.end();) {
    SimSensor& sensor = **it;
    if (sensor.link().model != id) {
      ++it;
      continue;
    }
    try {
      attach(sensor);
      ++it;
    } catch (const std::exception& e) {
      say(log_.error, owner + ": sensor '" + sensor.name() + "' left out: " + e.what());
      left_out[sensor.name()] = e.what();
      waitFrames();  // the frame in flight may be its own
      it = sensors_.erase(it);
    }
  }
  return left_out;
}

void SensorHost::removeModel(ModelId id) {
  waitFrames();  // the frame in flight may be one of its cameras'
  sensors_.erase(std::remove_if(sensors_.begin(), sensors_.end(),
                                [id](const std::unique_ptr<SimSensor>& s) {
                                  return s->link().model == id;
                                }),
                 sensors_.end());
}

SimSensor* SensorHost::find(ModelId id, const std::string& name) const {
  for (const auto& s : sensors_) {
    if (s->link().model == id && s->name() == name) return s.get();
  }
  return nullptr;
}

Renderer* SensorHost::ensureRenderer() {
  if (renderer_) return renderer_.get();
  if (renderer_failed_) return nullptr;
  try {
    renderer_ = std::make_unique<Renderer>(log_.warn);
    renderer_->setProfile(profile_);
    say(log_.info, "cameras render offscreen with " + renderer_->glInfo());
    return renderer_.get();
  } catch (const std::exception& e) {
    renderer_failed_ = true;
    say(log_.error, std::string("no offscreen rendering (") + e.what() +
                        "): the simulation runs on without cameras");
    return nullptr;
  }
}

void SensorHost::sense(double t) {
  for (const auto& s : sensors_) {
    const SimSensor::ProfileRows& rows = s->profileRows();
    SensorOutputs due;
    {
      StepProfile::Scope timed(profile_, rows.update);
      due = s->update(t, world_);
    }
    if (!due) continue;
    SensorListener* listener = s->listener();
    const SensorOutputs want = listener ? listener->wanted(*s, due) & due : due;
    const SensorOutputs counted = s->counted();
    if (due & counted) {
      SensorStat& stat = s->stat();
      if (want & counted) {
        ++stat.count;
        ++stat.renders;
      } else {
        ++stat.skipped;
        s->skip();
      }
    }
    if (!want) continue;
    {
      StepProfile::Scope timed(profile_, rows.sample);
      s->sample(want, world_);
    }
    const SensorOutputs now = want & ~s->rendered();
    if (now && listener) {
      StepProfile::Scope timed(profile_, rows.publish);
      listener->onOutputs(*s, now, t);
    }
  }
  submitFrames(t);
}

void SensorHost::submitFrames(double t) {
  // What is due and wanted was decided at the step; the frames are rendered (and handed to the
  // listeners) on the frame worker from a snapshot of this step's scene (frame_worker.h).
  if (due_frames_.empty()) return;
  if (frame_worker_) {
    // At most one frame in flight (frame_worker.h): the step waits here while the worker still
    // renders the last one (the profile's row shows how long).
    StepProfile::Scope timed(profile_, frame_wait_row_);
    frame_worker_->wait();
  }
  StepProfile::Scope timed(profile_, frames_row_);
  update_scene_();
  if (!frame_worker_) {
    frame_worker_ = std::make_unique<FrameWorker<FrameJob>>([this](FrameJob& job) {
      try {
        for (const FrameRequest& f : job.frames) {
          const SimSensor::ProfileRows& rows = f.sensor->profileRows();
          {
            StepProfile::Scope timed(profile_, rows.render);
            f.sensor->render(render_scene_, f);
          }
          if (SensorListener* l = f.sensor->listener()) {
            StepProfile::Scope timed(profile_, rows.frame_publish);
            l->onOutputs(*f.sensor, f.outputs, job.t);
          }
        }
      } catch (const std::exception& e) {
        say(log_.frame_error, std::string("camera frame not published: ") + e.what());
      }
    });
  }
  frame_worker_->submit([&](FrameJob& job) {
    job.t = t;
    job.frames.clear();
    std::swap(job.frames, due_frames_);
    snapshotScene(scene_, &render_scene_);
  });
}

void SensorHost::waitFrames() {
  if (frame_worker_) frame_worker_->wait();
}

void SensorHost::restart(double t) {
  for (const auto& s : sensors_) s->restart(t);
}

}  // namespace tianracer_sim
