// Camera frames off the stepping thread: a FrameWorker runs one job at a time on its own
// thread while the simulation steps on; snapshotScene() gives the job the scene as it was at
// the step the frame belongs to. ROS-free.
//
// Why: with the seed sensors the stepping thread spent most of its time waiting for llvmpipe's
// rasteriser threads and then adding noise, building the cloud and serialising, while physics,
// lidar and the other topics waited. With the frame rendered and published from here, the two
// overlap. Frames are the same bytes: they render the snapshot of their step, and jobs run in
// submission order (each sensor's noise generator advances in the same order as before).
#ifndef TIANRACER_SIM_SIM_FRAME_WORKER_H
#define TIANRACER_SIM_SIM_FRAME_WORKER_H

#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

#include "tianracer_sim/scene/scene.h"

namespace tianracer_sim {

/// Brings `to` to the state of `from`: a full copy when the bodies or items differ in number
/// (robots added or removed), else only the body poses and the lights (set_light_properties;
/// no allocation once warm). Items are set up once per robot or world load.
inline void snapshotScene(const Scene& from, Scene* to) {
  if (to->bodies.size() != from.bodies.size() || to->items.size() != from.items.size() ||
      to->lights.size() != from.lights.size()) {
    *to = from;
    return;
  }
  for (std::size_t i = 0; i < from.bodies.size(); ++i) to->bodies[i].X_WB = from.bodies[i].X_WB;
  for (std::size_t i = 0; i < from.lights.size(); ++i) {
    to->lights[i].direction = from.lights[i].direction;
    to->lights[i].diffuse = from.lights[i].diffuse;
    to->lights[i].specular = from.lights[i].specular;
  }
}

/// One background thread running jobs of type Job one at a time, in submission order, with at
/// most one in flight: submit() first waits for the previous job, so a frame never waits
/// behind more than one other and nothing queues up.
template <typename Job>
class FrameWorker {
 public:
  /// `run` is called on the worker thread with the submitted job.
  explicit FrameWorker(std::function<void(Job&)> run)
      : run_(std::move(run)), thread_([this] { loop(); }) {}

  /// Waits for the job in flight, then joins the thread.
  ~FrameWorker() {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      idle_.wait(lock, [this] { return !busy_; });
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

  FrameWorker(const FrameWorker&) = delete;
  FrameWorker& operator=(const FrameWorker&) = delete;

  /// Waits until the previous job is done, lets `fill(Job&)` write the next one (on the
  /// calling thread, while the worker is idle: it may also update what the job reads), then
  /// starts it and returns.
  template <typename Fill>
  void submit(Fill&& fill) {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return !busy_; });
    fill(job_);
    busy_ = true;
    lock.unlock();
    wake_.notify_one();
  }

  /// Waits until the job in flight (if any) is done.
  void wait() {
    std::unique_lock<std::mutex> lock(mutex_);
    idle_.wait(lock, [this] { return !busy_; });
  }

 private:
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return busy_ || stop_; });
      if (!busy_) return;  // stopped
      lock.unlock();
      run_(job_);
      lock.lock();
      busy_ = false;
      idle_.notify_all();
    }
  }

  std::function<void(Job&)> run_;
  Job job_;
  std::mutex mutex_;
  std::condition_variable wake_, idle_;
  bool busy_ = false;
  bool stop_ = false;
  std::thread thread_;  // last: started once everything above exists
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_SIM_FRAME_WORKER_H
