"""TianracerEnv: one robot in one world of tianracer sim as a Gymnasium environment.

The simulation is the ROS node's core without ROS (tianracer_sim.simulator.Simulation): the same
xacro, controller YAML, world and sensors, bit for bit what the node publishes at the same sim
time. docs/learning.md has the details; in short:

  observation  a Dict of the outputs named in `observe` (only those are computed): "odom"
               (13: position, quaternion x y z w in the world, linear and angular velocity in
               base_link), "joints" (3 x J: position, velocity, effort), "scan", "image",
               "depth", "imu", "ground_truth", a sensor name, or "<sensor>/<output>". A sensor
               holds its last sample between samples (its rate is the model's).
  action       Box: Ackermann (speed m/s, steering angle rad) through the cmd_vel node's maths,
               or action="commands": one command per controller (its URDF limits).
  reward       progress along the track's centreline (m) per step, or your callable
               reward(env, obs, info) -> float.
  terminated   on a collision (any contact but wheels on the ground); truncated at
               max_episode_time (s of sim time).
  reset(seed)  repeats exactly: the seed seeds the sensors' noise and the start pose (random on
               the centreline unless random_start=False or options={"pose": (x, y, yaw)}).
"""
import collections
import math
import os

import gymnasium as gym
import numpy as np
from gymnasium import spaces

from tianracer_sim import simulator

from . import packages, tracks

_TOLERANCE = 1e-9


def observation_space_of(sim):
    """The Dict space of a Simulation's observations (raw values: a lidar's -inf/+inf; a depth
    image's NaN (no return, or nearer than the near clip: Gazebo's and the ROS image's NaN) is
    +inf in the env's observation, as a Box cannot hold NaN)."""
    entries = collections.OrderedDict()  # in the order of `observe`
    for key, shape, dtype in sim.observation_specs:
        dtype = np.dtype(dtype)
        if dtype == np.uint8:
            entries[key] = spaces.Box(0, 255, shape, np.uint8)
        elif dtype == np.uint16:
            entries[key] = spaces.Box(0, 65535, shape, np.uint16)
        else:
            entries[key] = spaces.Box(-np.inf, np.inf, shape, dtype)
    return spaces.Dict(entries)


def _drain_warnings(log):
    for w in simulator.drain_warnings():
        log(w)


class TianracerEnv(gym.Env):
    metadata = {"render_modes": []}

    def __init__(self, model=None, model_args=(), urdf=None, model_dir="", robot_name="",
                 control_config=None, control_namespace="", controllers=(), world="racetrack",
                 observe=("scan", "odom"), action="ackermann", control_period=0.01,
                 reward="progress", centreline=None, max_episode_time=20.0, random_start=True,
                 terminate_on_collision=True, max_step_size=0.0, disable_sensors=(), seed=None,
                 timing=False, warn=None):
        super().__init__()
        if urdf is None and model is None:
            model = packages.default_model()
            if control_config is None:
                control_config = packages.default_control_config()
        self._warn = warn or (lambda w: None)
        # What the vector env needs to make more of the same without running xacro again.
        self.model_dir = model_dir if urdf is not None else os.path.dirname(os.path.abspath(model))
        self.control_config = control_config
        self.sim = simulator.Simulation(
            model=model or "", model_args=list(model_args), urdf=urdf or "", model_dir=model_dir,
            robot_name=robot_name, control_config=control_config or "",
            control_namespace=control_namespace, controllers=list(controllers), world=world,
            seed=0 if seed is None else int(seed), max_step_size=max_step_size,
            disable_sensors=list(disable_sensors), observe=list(observe), timing=timing)
        _drain_warnings(self._warn)

        # The control period: a whole number of physics steps.
        dt = self.sim.dt
        steps = control_period / dt if control_period > 0 and math.isfinite(control_period) else 0
        if not (steps >= 1 - _TOLERANCE and abs(steps - round(steps)) <= 1e-6 * steps):
            raise ValueError("control_period %r s is not a positive multiple of the physics step "
                             "%g s" % (control_period, dt))
        self.control_period = control_period
        self.steps_per_action = int(round(steps))

        # Actions.
        if action == "ackermann":
            drive = self.sim.ackermann
            if drive is None:
                raise ValueError("action='ackermann': " + self.sim.ackermann_problem +
                                 "; use action='commands'")
            self.action_space = spaces.Box(
                np.array([-drive["max_speed"], -drive["max_steering_right"]], np.float32),
                np.array([drive["max_speed"], drive["max_steering_left"]], np.float32),
                dtype=np.float32)
        elif action == "commands":
            commands = self.sim.commands
            if not commands:
                raise ValueError("action='commands': the robot has no controller with a command "
                                 "(give control_config)")
            self.action_space = spaces.Box(
                np.array([c["lower"] for c in commands], np.float32),
                np.array([c["upper"] for c in commands], np.float32), dtype=np.float32)
        else:
            raise ValueError("action must be 'ackermann' or 'commands', got %r" % (action,))
        self.action_mode = action
        # What every step reads: the bounds once, not through the space's properties.
        self._shape = self.action_space.shape
        self._low, self._high = self.action_space.low, self.action_space.high
        # Finite bounds: NaN and +-inf already fail the bounds test (one test per step).
        self._finite_bounds = bool(np.isfinite(self._low).all() and np.isfinite(self._high).all())
        self.observation_space = observation_space_of(self.sim)
        # The reward's position: from the observation when it holds the odometry (the same
        # numbers, SimEnv::odom), else one more call.
        self._odom_in_obs = "odom" in self.observation_space.spaces
        self._depth_keys = [k for k, kind in self.sim.observation_kinds.items() if kind == "depth"]

        # Reward, start poses, limits.
        if centreline is None:
            self.centreline = tracks.centreline_for(world)
        else:
            self.centreline = tracks.make_centreline(centreline)
        if reward == "progress":
            if self.centreline is None:
                raise ValueError("reward='progress' needs a centreline: world %r has none shipped; "
                                 "pass centreline=[(x, y), ...] or reward=<callable>" % (world,))
            self._reward = None
        elif callable(reward):
            self._reward = reward
        else:
            raise ValueError("reward must be 'progress' or a callable reward(env, obs, info), got %r"
                             % (reward,))
        if not (max_episode_time > 0):
            raise ValueError("max_episode_time must be > 0 s, got %r" % (max_episode_time,))
        self.max_episode_time = float(max_episode_time)
        self.random_start = bool(random_start)
        self.terminate_on_collision = bool(terminate_on_collision)
        self._s = 0.0
        self._segment = -1
        self.progress = 0.0
        self._has_reset = False

    # -- the Gymnasium API ----------------------------------------------------------------
    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        if seed is not None:
            self.sim.reseed(int(seed))
        pose = (options or {}).get("pose")
        if pose is None and self.random_start and self.centreline is not None:
            x, y, yaw = self.centreline.pose(self.np_random.uniform(0.0, self.centreline.length))
            pose = (x, y, yaw)
        self.sim.reset(pose=None if pose is None else [float(v) for v in pose])
        _drain_warnings(self._warn)
        self._start_tracking()
        self._has_reset = True
        obs = self._observation()
        return obs, self._info(False)

    def step(self, action):
        if not self._has_reset:
            raise RuntimeError("call reset() before step()")
        self._apply(self._checked(action))
        contacts = self.sim.step(self.steps_per_action)
        obs = self._observation()
        return self._outcome(obs, contacts)

    # -- shared with the vector env ---------------------------------------------------------
    def _checked(self, action):
        a = np.asarray(action, dtype=np.float64)
        if a.shape != self._shape:
            raise ValueError("action %r has shape %s; the action space is %s" %
                             (action, a.shape, self.action_space))
        if not self._within_bounds(a):
            if not np.isfinite(a).all():
                raise ValueError("action %r is not finite" % (action,))
            raise ValueError("action %s is outside the action space [%s, %s]" %
                             (a.tolist(), self._low.tolist(), self._high.tolist()))
        return a

    def _within_bounds(self, a):
        """Whether each action (the last axis; a batch of rows too) is finite and within the
        space's bounds. Bounds are float32: compared there, so that a float32 action at a bound
        is inside; NaN and +-inf fail finite bounds, so finiteness is tested only without them."""
        a32 = a.astype(np.float32)
        ok = ((a32 >= self._low) & (a32 <= self._high)).all(axis=-1)
        return ok if self._finite_bounds else ok & np.isfinite(a).all(axis=-1)

    def _apply(self, a):
        if self.action_mode == "ackermann":
            self.sim.set_ackermann(float(a[0]), float(a[1]))
        else:
            self.sim.set_commands(a)

    def _observation(self):
        obs = self.sim.observation()
        self._fix(obs)
        return obs

    def _fix(self, obs):
        for k in self._depth_keys:
            np.nan_to_num(obs[k], copy=False, nan=np.inf)

    def _start_tracking(self):
        self.progress = 0.0
        if self.centreline is not None:
            x, y = self.sim.odom()[:2]
            self._s, _, self._segment = self.centreline.project(x, y)

    def _outcome(self, obs, contacts):
        """Reward, terminated, truncated and info after a step (obs: this env's values)."""
        if self.centreline is not None:
            odom = obs["odom"] if self._odom_in_obs else self.sim.odom()
            s, _, self._segment = self.centreline.project(odom[0], odom[1], self._segment)
            delta = self.centreline.advance(self._s, s)
            self._s = s
            self.progress += delta
        else:
            delta = 0.0
        collision = contacts > 0
        info = self._info(collision)
        reward = delta if self._reward is None else float(self._reward(self, obs, info))
        terminated = bool(collision and self.terminate_on_collision)
        truncated = bool(self.sim.time >= self.max_episode_time - _TOLERANCE)
        return obs, reward, terminated, truncated, info

    def _info(self, collision):
        return {"time": self.sim.time, "progress": self.progress, "collision": bool(collision)}
