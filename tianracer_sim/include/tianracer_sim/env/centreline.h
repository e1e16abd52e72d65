// A track's centreline as a polyline: where a point is along it (arc length) and the pose at
// an arc length. The learning environment's progress reward and start poses. ROS-free.
#ifndef TIANRACER_SIM_ENV_CENTRELINE_H
#define TIANRACER_SIM_ENV_CENTRELINE_H

#include <stdexcept>
#include <vector>

#include <Eigen/Core>

namespace tianracer_sim {

class Centreline {
 public:
  /// At least two distinct points, all finite; `closed`: the last point joins the first (a
  /// lap). Throws std::invalid_argument naming the problem.
  Centreline(std::vector<Eigen::Vector2d> points, bool closed);

  double length() const { return cumulative_.back(); }
  bool closed() const { return closed_; }
  const std::vector<Eigen::Vector2d>& points() const { return points_; }

  struct Projection {
    double s = 0.0;        // arc length of the nearest point (m), in [0, length())
    double lateral = 0.0;  // signed distance, + left of the direction of travel (m)
    int segment = 0;       // the segment it lies on (a hint for the next call)
  };
  /// The nearest point of the line to p. With hint >= 0 (the last projection's segment) only
  /// the segments within `window` of it are searched (a car moves little between calls);
  /// hint < 0 searches all.
  Projection project(const Eigen::Vector2d& p, int hint = -1, int window = 20) const;

  /// Arc length travelled from s0 to s1: s1 - s0, on a closed line the shorter way round
  /// (wrapped into [-length/2, length/2)).
  double advance(double s0, double s1) const;

  /// The point at arc length s (wrapped on a closed line, clamped on an open one) and the
  /// heading of its segment (rad, atan2).
  Eigen::Vector3d pose(double s) const;

 private:
  std::vector<Eigen::Vector2d> points_;
  std::vector<double> cumulative_;  // arc length at each point; back() = length
  bool closed_;
  int segments_;
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_ENV_CENTRELINE_H
