// <actor> scripts played as Gazebo 11 plays them (include/tianracer_sim/world/actor.h has the
// sources). The splines are written from their published definitions (cubic Hermite with
// Catmull-Rom tangents scaled by 1 - tension; Shoemake's squad), in ignition-math6's conventions.
#include "tianracer_sim/world/actor.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace tianracer_sim {

namespace {

using Quat = Eigen::Quaterniond;

// ignition::math::equal's default tolerance.
bool near(double a, double b, double tol = 1e-6) { return std::abs(a - b) <= tol; }

Quat add(const Quat& a, const Quat& b) {
  return Quat(a.w() + b.w(), a.x() + b.x(), a.y() + b.y(), a.z() + b.z());
}
Quat scale(const Quat& a, double s) { return Quat(a.w() * s, a.x() * s, a.y() * s, a.z() * s); }
double dot(const Quat& a, const Quat& b) {
  return a.w() * b.w() + a.x() * b.x() + a.y() * b.y() + a.z() * b.z();
}

// Quaternion::Inverse: the conjugate over the squared norm.
Quat inverse(const Quat& q) {
  const double s = dot(q, q);
  if (near(s, 0.0)) return Quat::Identity();
  return Quat(q.w() / s, -q.x() / s, -q.y() / s, -q.z() / s);
}

// Quaternion::Log of a unit quaternion: (0, angle / sin(angle) * v), angle = acos(w).
Quat logOf(const Quat& q) {
  if (std::abs(q.w()) < 1.0) {
    const double angle = std::acos(q.w());
    const double s = std::sin(angle);
    if (std::abs(s) >= 1e-3) {
      const double c = angle / s;
      return Quat(0.0, c * q.x(), c * q.y(), c * q.z());
    }
  }
  return Quat(0.0, q.x(), q.y(), q.z());
}

// Quaternion::Exp of a pure quaternion (not normalised, as there).
Quat expOf(const Quat& q) {
  const double angle = std::sqrt(q.x() * q.x() + q.y() * q.y() + q.z() * q.z());
  const double s = std::sin(angle);
  const double c = std::abs(s) >= 1e-3 ? s / angle : 1.0;
  return Quat(std::cos(angle), c * q.x(), c * q.y(), c * q.z());
}

// Quaternion::Slerp: spherical interpolation, normalised lerp when the two nearly coincide.
Quat slerp(double t, const Quat& p, const Quat& q, bool shortest) {
  double c = dot(p, q);
  Quat r = q;
  if (c < 0.0 && shortest) {
    c = -c;
    r = scale(q, -1.0);
  }
  if (std::abs(c) < 1.0 - 1e-3) {
    const double s = std::sqrt(1.0 - c * c);
    const double angle = std::atan2(s, c);
    return add(scale(p, std::sin((1.0 - t) * angle) / s), scale(r, std::sin(t * angle) / s));
  }
  Quat out = add(scale(p, 1.0 - t), scale(r, t));
  out.normalize();
  return out;
}

Quat squad(double t, const Quat& p, const Quat& a, const Quat& b, const Quat& q) {
  return slerp(2.0 * t * (1.0 - t), slerp(t, p, q, true), slerp(t, a, b, false), false);
}

bool sameQuat(const Quat& a, const Quat& b) {  // Quaternion::operator== (tolerance 1e-3)
  return near(a.w(), b.w(), 1e-3) && near(a.x(), b.x(), 1e-3) && near(a.y(), b.y(), 1e-3) &&
         near(a.z(), b.z(), 1e-3);
}

Eigen::Vector3d positionAt(const std::vector<ActorWaypoint>& w, std::size_t k, double s,
                           double tension) {
  const std::size_t n = w.size();
  if (k + 1 >= n || near(s, 0.0)) return w[std::min(k, n - 1)].position;
  if (near(s, 1.0)) return w[k + 1].position;
  const bool closed = (w[0].position - w[n - 1].position).cwiseAbs().maxCoeff() <= 1e-6;
  const double f = 0.5 * (1.0 - tension);
  auto tangent = [&](std::size_t i) -> Eigen::Vector3d {
    if (i == 0) {
      return f * (w[1].position - (closed ? w[n - 2].position : w[0].position));
    }
    if (i == n - 1) {
      return closed ? Eigen::Vector3d(f * (w[1].position - w[n - 2].position))
                    : Eigen::Vector3d(f * (w[i].position - w[i - 1].position));
    }
    return f * (w[i + 1].position - w[i - 1].position);
  };
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * w[k].position + (-2 * s3 + 3 * s2) * w[k + 1].position +
         (s3 - 2 * s2 + s) * tangent(k) + (s3 - s2) * tangent(k + 1);
}

Quat rotationAt(const std::vector<ActorWaypoint>& w, std::size_t k, double s) {
  const std::size_t n = w.size();
  if (k + 1 >= n || near(s, 0.0)) return w[std::min(k, n - 1)].rotation;
  if (near(s, 1.0)) return w[k + 1].rotation;
  const bool closed = sameQuat(w[0].rotation, w[n - 1].rotation);
  auto tangent = [&](std::size_t i) {
    const Quat& p = w[i].rotation;
    const Quat inv = inverse(p);
    Quat part1, part2;
    if (i == 0) {
      part1 = logOf(inv * w[1].rotation);
      part2 = logOf(inv * (closed ? w[n - 2].rotation : p));
    } else if (i == n - 1) {
      part1 = logOf(inv * (closed ? w[1].rotation : p));
      part2 = logOf(inv * w[i - 1].rotation);
    } else {
      part1 = logOf(inv * w[i + 1].rotation);
      part2 = logOf(inv * w[i - 1].rotation);
    }
    return Quat(p * expOf(scale(add(part1, part2), -0.25)));
  };
  return squad(s, w[k].rotation, tangent(k), tangent(k + 1), w[k + 1].rotation);
}

}  // namespace

Eigen::Quaterniond actorRotation(double roll, double pitch, double yaw) {
  const double cp = std::cos(roll / 2), sp = std::sin(roll / 2);
  const double ct = std::cos(pitch / 2), st = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  Quat q(cp * ct * cy + sp * st * sy, sp * ct * cy - cp * st * sy, cp * st * cy + sp * ct * sy,
         cp * ct * sy - sp * st * cy);
  q.normalize();
  return q;
}

Eigen::Isometry3d trajectoryPose(const ActorTrajectory& trajectory, double time) {
  const std::vector<ActorWaypoint>& w = trajectory.waypoints;
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  if (w.empty()) return X;
  // The keyframes: the first at 0, the others at their times; the length is the last time.
  auto keyTime = [&](std::size_t i) { return i == 0 ? 0.0 : w[i].time; };
  const double length = w.back().time;
  time = std::clamp(time, 0.0, std::max(length, 0.0));  // Animation::SetTime, loop false
  // Animation::GetKeyFramesAtTime: the first keyframe at or after `time` (lower_bound), the
  // one before it unless `time` is on it.
  std::size_t hi = 0;
  while (hi < w.size() && keyTime(hi) < time) ++hi;
  std::size_t k;
  double t1, t2;
  if (hi == w.size()) {  // past the last keyframe: wraps to the first
    k = w.size() - 1;
    t1 = keyTime(k);
    t2 = length + keyTime(0);
  } else {
    k = (hi != 0 && time < keyTime(hi)) ? hi - 1 : hi;
    t1 = keyTime(k);
    t2 = keyTime(hi);
  }
  const double s = near(t1, t2) ? 0.0 : (time - t1) / (t2 - t1);
  X.translation() = positionAt(w, k, s, trajectory.tension);
  X.linear() = rotationAt(w, k, s).normalized().toRotationMatrix();
  return X;
}

ActorPlayer::ActorPlayer(ActorScript script, const Eigen::Isometry3d& X_start, double dt)
    : script_(std::move(script)), X_start_(X_start),
      dt_ns_(std::max<std::int64_t>(1, std::llround(dt * 1e9))) {
  for (const ActorTrajectory& tr : script_.trajectories) {
    starts_.push_back(length_);
    length_ += tr.waypoints.empty() ? 0.0 : tr.waypoints.back().time;
  }
  reset();
}

void ActorPlayer::reset() {
  step_ = 0;
  prev_frame_ns_ = 0;  // Actor::Init: the sim time at load
  play_start_ns_ = 0;
  active_ = script_.auto_start || play_requested_;
  X_ = X_start_;
}

void ActorPlayer::play() {
  play_requested_ = true;
  active_ = true;
  play_start_ns_ = step_ * dt_ns_;
}

const Eigen::Isometry3d& ActorPlayer::poseAt(double t) {
  if (!(t >= 0.0)) t = 0.0;
  const std::int64_t target = std::llround(std::min(t, 1e9) * 1e9) / dt_ns_;
  if (target < step_) reset();
  while (step_ < target) {
    ++step_;
    update(step_ * dt_ns_);
  }
  return X_;
}

void ActorPlayer::update(std::int64_t t_ns) {
  if (!active_ || script_.trajectories.empty()) return;
  if (static_cast<double>(t_ns - prev_frame_ns_) * 1e-9 < 1.0 / 30.0) return;  // 30 Hz
  double script_time = static_cast<double>(t_ns - play_start_ns_) * 1e-9 - script_.delay_start;
  if (script_time < 0.0) return;  // waiting for delay_start
  if (script_time >= length_) {
    if (!script_.loop) {
      active_ = false;
      return;
    }
    script_time -= length_;
    play_start_ns_ = t_ns - std::llround(script_time * 1e9);
  }
  // The trajectory playing at this time (the first whose span holds it).
  const ActorTrajectory* tr = nullptr;
  double start = 0.0;
  for (std::size_t i = 0; i < script_.trajectories.size(); ++i) {
    const double end = starts_[i] + (script_.trajectories[i].waypoints.empty()
                                         ? 0.0
                                         : script_.trajectories[i].waypoints.back().time);
    if (starts_[i] <= script_time && end >= script_time) {
      tr = &script_.trajectories[i];
      start = starts_[i];
      break;
    }
  }
  if (!tr) return;  // Gazebo: "Trajectory not found at time" (a zero-length looping script)
  prev_frame_ns_ = t_ns;
  X_ = trajectoryPose(*tr, script_time - start);
}

}  // namespace tianracer_sim
