// A fixed set of threads that runs job(i) for i in [0, n) and returns when all are done: the
// vector environment steps its simulations on it (each simulation on one thread at a time).
// ROS-free.
#ifndef TIANRACER_SIM_ENV_PARALLEL_H
#define TIANRACER_SIM_ENV_PARALLEL_H

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace tianracer_sim {

class ParallelFor {
 public:
  /// `threads` >= 1 threads in all, the caller's included (threads - 1 are started).
  explicit ParallelFor(int threads);
  ~ParallelFor();
  ParallelFor(const ParallelFor&) = delete;
  ParallelFor& operator=(const ParallelFor&) = delete;

  int threads() const { return static_cast<int>(workers_.size()) + 1; }
  /// Runs job(i) once for each i in [0, n), on the workers and the calling thread; returns
  /// when every call has returned. The first exception a job throws is rethrown here (after
  /// all calls ended). Not reentrant: one run() at a time.
  void run(int n, const std::function<void(int)>& job);

 private:
  void work();
  void drain();

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable start_, done_;
  const std::function<void(int)>* job_ = nullptr;
  int n_ = 0, next_ = 0, running_ = 0;
  unsigned generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ENV_PARALLEL_H
