#include "tianracer_sim/env/parallel.h"

namespace tianracer_sim {

ParallelFor::ParallelFor(int threads) {
  for (int k = 1; k < threads; ++k) workers_.emplace_back([this] { work(); });
}

ParallelFor::~ParallelFor() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  start_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ParallelFor::drain() {
  // Takes indices until none is left; called with mutex_ held, returns with it held.
  std::unique_lock<std::mutex> lock(mutex_, std::adopt_lock);
  while (next_ < n_) {
    const int i = next_++;
    ++running_;
    lock.unlock();
    try {
      (*job_)(i);
    } catch (...) {
      std::lock_guard<std::mutex> guard(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    lock.lock();
    --running_;
  }
  lock.release();
}

void ParallelFor::work() {
  unsigned seen = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    start_.wait(lock, [&] { return stop_ || generation_ != seen; });
    if (stop_) return;
    seen = generation_;
    lock.release();  // drain() adopts the held lock
    drain();
    lock = std::unique_lock<std::mutex>(mutex_, std::adopt_lock);
    if (next_ >= n_ && running_ == 0) done_.notify_all();
  }
}

void ParallelFor::run(int n, const std::function<void(int)>& job) {
  if (n <= 0) return;
  std::unique_lock<std::mutex> lock(mutex_);
  job_ = &job;
  n_ = n;
  next_ = 0;
  running_ = 0;
  error_ = nullptr;
  ++generation_;
  start_.notify_all();
  lock.release();
  drain();  // the caller works too
  lock = std::unique_lock<std::mutex>(mutex_, std::adopt_lock);
  done_.wait(lock, [&] { return next_ >= n_ && running_ == 0; });
  job_ = nullptr;
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

}  // namespace tianracer_sim
