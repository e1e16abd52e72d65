// Where a step's time goes: named rows of wall time (steady clock) and call counts, filled by
// scoped timers on the stepping thread and on the frame worker, read as a table per step.
//
// Off by default: code holds a `StepProfile*` that is null unless profiling was asked for
// (SimulatorOptions::profile, the node's ~profile), and a Scope on a null profile does nothing
// but one test of the pointer. Rows are registered by name at set-up (row() takes a lock and
// may allocate); add() is lock-free (relaxed atomics on a fixed array of kMaxRows rows), so
// both threads add to one profile while a third registers or reads.
//
// A row named "parent / child" is a part of row "parent" (the lidar's publication: its
// conversion to a message, its serialisation and sending); the table indents it and the
// step's total counts only the top-level rows.
#ifndef TIANRACER_SIM_COMMON_STEP_PROFILE_H
#define TIANRACER_SIM_COMMON_STEP_PROFILE_H

#include <atomic>
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace tianracer_sim {

class StepProfile {
 public:
  using Clock = std::chrono::steady_clock;

  /// Rows of the stepping thread that every simulation has (the node and the Simulator fill
  /// them); sensors, publishers and the frame worker add their own with row().
  static constexpr const char* kStep = "step (all of it)";
  static constexpr const char* kBullet = "physics: Bullet stepSimulation";
  static constexpr const char* kControllers = "physics: controllers";
  static constexpr const char* kContactScan = "contacts: scan of the step's manifolds";
  /// Rows whose names start so run on the stepping thread between two steps (callbacks,
  /// status): the step's cost outside Bullet counts them with the kStep row.
  static constexpr const char* kBetweenSteps = "between steps: ";
  /// Rows whose names start so run on the frame worker's thread, alongside the steps.
  static constexpr const char* kFrameWorker = "frame worker: ";

  static constexpr int kMaxRows = 256;

  StepProfile() : rows_(new Row[kMaxRows]) {}

  /// The row's index, registered on first use. Names are kept in registration order; past
  /// kMaxRows names, the last row ("other") takes them all.
  int row(const std::string& name);

  void add(int row, Clock::duration d) {
    Row& r = rows_[row];
    r.ns.fetch_add(std::chrono::duration_cast<std::chrono::nanoseconds>(d).count(),
                   std::memory_order_relaxed);
    r.calls.fetch_add(1, std::memory_order_relaxed);
  }
  /// One more step of the simulation (the table's per-step figures divide by this).
  void countStep() { steps_.fetch_add(1, std::memory_order_relaxed); }
  std::uint64_t steps() const { return steps_.load(std::memory_order_relaxed); }
  /// Forgets the figures (not the rows).
  void reset();

  struct Figure {
    std::string name;
    double seconds = 0.0;
    std::uint64_t calls = 0;
    bool part = false;  // "parent / child"
  };
  /// The rows' figures so far, in registration order.
  std::vector<Figure> figures() const;
  /// A text table: per row, µs per step, calls per step and µs per call; then the stepping
  /// thread's time per step outside Bullet (kStep and the between-steps rows, less kBullet).
  /// Rows never called are left out.
  std::string table() const;

  /// Times its scope into a row; nothing when the profile is null.
  class Scope {
   public:
    Scope(StepProfile* profile, int row) : profile_(profile), row_(row) {
      if (profile_) start_ = Clock::now();
    }
    ~Scope() {
      if (profile_) profile_->add(row_, Clock::now() - start_);
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StepProfile* profile_;
    int row_;
    Clock::time_point start_;
  };

 private:
  struct Row {
    std::string name;
    std::atomic<std::int64_t> ns{0};
    std::atomic<std::uint64_t> calls{0};
  };
  mutable std::mutex mutex_;  // row registration
  std::unique_ptr<Row[]> rows_;
  std::atomic<int> count_{0};  // rows registered (names set before the count says so)
  std::atomic<std::uint64_t> steps_{0};
};

/// The row of `name` in `profile`, or -1 when there is no profile.
inline int profileRow(StepProfile* profile, const std::string& name) {
  return profile ? profile->row(name) : -1;
}

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_COMMON_STEP_PROFILE_H
