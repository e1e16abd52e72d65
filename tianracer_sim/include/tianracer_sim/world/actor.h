// <actor> as Gazebo 11 plays it without a skin: its <script> of <trajectory>s moves the actor's
// <link>s in sim time (docs/actors.md). ROS-free.
//
// Sources (Gazebo 11.10.2, gazebo/physics/Actor.cc, gazebo/common/Animation.cc; the splines are
// ignition-math6's Spline and RotationSpline):
//  - Actor::LoadScript: trajectories are played one after another in ascending `id` (equal ids
//    in file order); a trajectory's waypoints are sorted by <time>; its first keyframe is at
//    time 0 whatever the first waypoint's <time>; its duration is the last waypoint's <time>.
//  - Actor::Update: runs after each step with the new sim time t, at most every 1/30 s of sim
//    time (t - t_prev >= 1/30, t_prev starting at the time the actor was loaded); the script
//    time is t - delay_start - t_play (t_play: when Play() was called, at load when auto_start);
//    before delay_start the actor stays where it is; past the script's length it stops
//    (loop false) or starts over (loop true: t_play = t - (script time - length)).
//  - Actor::Update without a skin: SetWorldPose(the interpolated waypoint pose); the actor's
//    own <pose> is where it stands until the first frame.
//  - PoseAnimation::GetInterpolatedKeyFrame: between keyframes k and k+1 at parameter
//    s = (t - t_k) / (t_{k+1} - t_k), position = a cubic Hermite spline through the waypoints
//    with tangents (1 - tension) (p_{k+1} - p_{k-1}) / 2 (Spline::RecalcTangents; one-sided at
//    the ends, wrapped when the first and last points are equal), rotation = squad through the
//    waypoints' quaternions with Shoemake's tangents (RotationSpline::RecalcTangents), the
//    shortest way.
#ifndef TIANRACER_SIM_WORLD_ACTOR_H
#define TIANRACER_SIM_WORLD_ACTOR_H

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace tianracer_sim {

struct ActorWaypoint {
  double time = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  /// From <pose>'s roll pitch yaw as ignition::math::Quaterniond(roll, pitch, yaw) makes it
  /// (its sign matters to the squad tangents): see actorRotation.
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  int line = 0;
};

struct ActorTrajectory {
  int id = 0;
  std::string type;
  double tension = 0.0;
  std::vector<ActorWaypoint> waypoints;  // sorted by time (the first is played at 0)
  int line = 0;
};

/// <script>; defaults are SDF 1.6's (sdf/1.6/actor.sdf).
struct ActorScript {
  bool loop = true;
  double delay_start = 0.0;
  bool auto_start = true;
  std::vector<ActorTrajectory> trajectories;  // in play order (ascending id)
};

/// ignition::math::Quaterniond(roll, pitch, yaw) (Quaternion::Euler): the half-angle product
/// with w = cos cos cos + sin sin sin, then normalised.
Eigen::Quaterniond actorRotation(double roll, double pitch, double yaw);

/// One trajectory's pose at `time` (s since it began; clamped to [0, duration] as Gazebo's
/// non-looping PoseAnimation::SetTime does): Gazebo's spline and squad (above).
Eigen::Isometry3d trajectoryPose(const ActorTrajectory& trajectory, double time);

/// An actor's script played as Actor::Update plays it, step by step in sim time.
class ActorPlayer {
 public:
  /// `X_start`: the actor's <pose>, where it stands until its first frame; `dt`: the physics
  /// step (Actor::Update runs after each).
  ActorPlayer(ActorScript script, const Eigen::Isometry3d& X_start, double dt);

  /// Runs Actor::Update for every step up to sim time `t` (s; the steps are k * dt) and returns
  /// the actor's pose then. `t` before the last call: the player starts over from 0 (a world
  /// reset).
  const Eigen::Isometry3d& poseAt(double t);
  /// Actor::Play (auto_start false waits for it: in Gazebo only a plugin or C++ API calls it).
  void play();
  bool active() const { return active_; }
  /// Sum of the trajectories' durations.
  double scriptLength() const { return length_; }
  const ActorScript& script() const { return script_; }

 private:
  void reset();
  void update(std::int64_t t_ns);

  ActorScript script_;
  Eigen::Isometry3d X_start_;
  std::int64_t dt_ns_;
  double length_ = 0.0;
  std::vector<double> starts_;  // each trajectory's start in the script
  // Actor::Update's state.
  std::int64_t step_ = 0;  // steps run
  std::int64_t prev_frame_ns_ = 0, play_start_ns_ = 0;
  bool active_ = true;
  bool play_requested_ = false;
  Eigen::Isometry3d X_ = Eigen::Isometry3d::Identity();
};

}  // namespace tianracer_sim

#endif  // TIANRACER_SIM_WORLD_ACTOR_H
