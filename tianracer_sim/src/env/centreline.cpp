#include "tianracer_sim/env/centreline.h"

#include <cmath>
#include <limits>
#include <string>

namespace tianracer_sim {

Centreline::Centreline(std::vector<Eigen::Vector2d> points, bool closed)
    : points_(std::move(points)), closed_(closed) {
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (!points_[i].allFinite()) {
      throw std::invalid_argument("centreline: point " + std::to_string(i) + " is not finite");
    }
  }
  // A closed line given with its first point repeated at the end: drop the repeat.
  if (closed_ && points_.size() > 2 && (points_.back() - points_.front()).norm() < 1e-12) {
    points_.pop_back();
  }
  if (points_.size() < 2) throw std::invalid_argument("centreline: needs at least 2 points");
  segments_ = static_cast<int>(points_.size()) - (closed_ ? 0 : 1);
  cumulative_.assign(1, 0.0);
  for (int i = 0; i < segments_; ++i) {
    const double d = (points_[(i + 1) % points_.size()] - points_[i]).norm();
    cumulative_.push_back(cumulative_.back() + d);
  }
  if (!(length() > 0.0)) throw std::invalid_argument("centreline: all points coincide");
}

Centreline::Projection Centreline::project(const Eigen::Vector2d& p, int hint, int window) const {
  Projection best;
  double best_d2 = std::numeric_limits<double>::infinity();
  const int n = segments_;
  const bool all = hint < 0 || 2 * window + 1 >= n;
  const int count = all ? n : 2 * window + 1;
  const int first = all ? 0 : hint - window;
  for (int k = 0; k < count; ++k) {
    int i = first + k;
    if (closed_) {
      i = ((i % n) + n) % n;
    } else if (i < 0 || i >= n) {
      continue;
    }
    const Eigen::Vector2d& a = points_[i];
    const Eigen::Vector2d& b = points_[(i + 1) % points_.size()];
    const Eigen::Vector2d ab = b - a;
    const double len2 = ab.squaredNorm();
    double u = len2 > 0.0 ? (p - a).dot(ab) / len2 : 0.0;
    u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
    const Eigen::Vector2d q = a + u * ab;
    const double d2 = (p - q).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best.segment = i;
      best.s = cumulative_[i] + u * std::sqrt(len2);
      const double cross = ab.x() * (p - a).y() - ab.y() * (p - a).x();
      best.lateral = std::copysign(std::sqrt(d2), cross);
    }
  }
  if (closed_ && best.s >= length()) best.s -= length();
  return best;
}

double Centreline::advance(double s0, double s1) const {
  double d = s1 - s0;
  if (closed_) {
    const double L = length();
    d = std::fmod(d + 0.5 * L, L);
    if (d < 0.0) d += L;
    d -= 0.5 * L;
  }
  return d;
}

Eigen::Vector3d Centreline::pose(double s) const {
  const double L = length();
  if (closed_) {
    s = std::fmod(s, L);
    if (s < 0.0) s += L;
  } else {
    s = s < 0.0 ? 0.0 : (s > L ? L : s);
  }
  int i = 0;
  while (i + 1 < segments_ && cumulative_[i + 1] <= s) ++i;
  const Eigen::Vector2d& a = points_[i];
  const Eigen::Vector2d& b = points_[(i + 1) % points_.size()];
  const double len = cumulative_[i + 1] - cumulative_[i];
  const double u = len > 0.0 ? (s - cumulative_[i]) / len : 0.0;
  const Eigen::Vector2d q = a + u * (b - a);
  return Eigen::Vector3d(q.x(), q.y(), std::atan2(b.y() - a.y(), b.x() - a.x()));
}

}  // namespace tianracer_sim
