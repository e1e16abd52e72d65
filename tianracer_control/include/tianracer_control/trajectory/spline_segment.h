// joint_trajectory_controller's trajectory segment and its sampling (ros_controllers noetic-devel,
// trajectory_interface/quintic_spline_segment.h and trajectory_interface.h). ROS-free.
#ifndef TIANRACER_CONTROL_TRAJECTORY_SPLINE_SEGMENT_H
#define TIANRACER_CONTROL_TRAJECTORY_SPLINE_SEGMENT_H

#include <array>
#include <cstddef>
#include <vector>

namespace tianracer_control {
namespace trajectory {

/// Position, velocity and acceleration of n joints (trajectory_interface::PosVelAccState). An
/// empty velocity or acceleration means "not given".
struct State {
  State() = default;
  /// n zeros in each of the three.
  explicit State(std::size_t n) : position(n, 0.0), velocity(n, 0.0), acceleration(n, 0.0) {}

  std::vector<double> position;
  std::vector<double> velocity;
  std::vector<double> acceleration;
  double time_from_start = 0.0;  // of the waypoint it was made from [s]
};

/// A multi-dimensional spline from `start_state` at `start_time` to `end_state` at `end_time`
/// (QuinticSplineSegment). Per dimension, with T = end - start and s = t - start:
///   only positions given (in either state):  p(s) = p0 + (p1 - p0)/T s          (linear)
///   positions and velocities:                cubic, p(0)=p0 p'(0)=v0 p(T)=p1 p'(T)=v1
///   positions, velocities, accelerations:    quintic, also p''(0)=a0 p''(T)=a1
/// The lowest level both states give is used. T = 0 gives the start state's terms only.
/// Sampling before the start gives the start position, after the end the end position, both
/// with zero velocity and acceleration; inside [start, end] the polynomial and its derivatives.
class SplineSegment {
 public:
  /// An empty segment: size() 0; sampling it gives empty vectors.
  SplineSegment() = default;
  /// Throws std::invalid_argument (upstream's messages) when end < start, a position list is
  /// empty, or the sizes differ.
  SplineSegment(double start_time, const State& start_state, double end_time,
                const State& end_state);

  void init(double start_time, const State& start_state, double end_time,
            const State& end_state);
  /// Resizes `state` to size() and fills position, velocity and acceleration.
  void sample(double time, State& state) const;

  double startTime() const { return start_time_; }
  double endTime() const { return start_time_ + duration_; }
  /// The start state's time_from_start.
  double timeFromStart() const { return time_from_start_; }
  std::size_t size() const { return coefs_.size(); }

 private:
  /// c0 + c1 s + c2 s^2 + c3 s^3 + c4 s^4 + c5 s^5
  using Coefficients = std::array<double, 6>;
  std::vector<Coefficients> coefs_;
  double duration_ = 0.0;
  double start_time_ = 0.0;
  double time_from_start_ = 0.0;
};

/// The segments of one joint, sorted by start time (what the controller keeps per joint).
template <class Segment>
using SegmentList = std::vector<Segment>;

/// The segment that holds `time`: the last one whose start time is <= time; `segments.end()`
/// when the list is empty or time is before the first start (trajectory_interface::findSegment).
template <class Segment>
typename std::vector<Segment>::const_iterator findSegment(const std::vector<Segment>& segments,
                                                          double time) {
  auto it = segments.begin();
  if (it == segments.end() || time < it->startTime()) return segments.end();
  // upper_bound on start time, then one back
  std::size_t lo = 0, hi = segments.size();
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (time < segments[mid].startTime()) hi = mid; else lo = mid + 1;
  }
  return segments.begin() + static_cast<std::ptrdiff_t>(lo - 1);
}

/// Samples the segment that holds `time` (trajectory_interface::sample). Before the first
/// segment it samples the first one (its start, held) but still returns end(), which callers
/// treat as "no trajectory at this time".
template <class Segment>
typename std::vector<Segment>::const_iterator sampleSegments(const std::vector<Segment>& segments,
                                                             double time, State& state) {
  auto it = findSegment(segments, time);
  if (it != segments.end()) {
    it->sample(time, state);
  } else if (!segments.empty()) {
    segments.front().sample(time, state);
  }
  return it;
}

}  // namespace trajectory
}  // namespace tianracer_control

#endif  // TIANRACER_CONTROL_TRAJECTORY_SPLINE_SEGMENT_H
