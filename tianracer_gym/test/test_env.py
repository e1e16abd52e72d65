"""TianracerEnv without ROS: spaces, determinism of reset(seed), collisions, time limits, what is
computed, and bad input with its message."""
import math
import unittest

import os
import sys

# catkin runs nosetests with -P (no path adjustment): the test folder's helpers by path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import support  # noqa: F401  (ROS_PACKAGE_PATH)
from support import same

import gymnasium as gym
import numpy as np

import tianracer_gym
from tianracer_gym import TianracerEnv, packages


def gym_model_env(**kwargs):
    kwargs.setdefault('model', packages.gym_model())
    kwargs.setdefault('control_config', packages.default_control_config())
    kwargs.setdefault('observe', ('scan', 'odom', 'camera_small', 'joints'))
    return TianracerEnv(**kwargs)


class Spaces(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.env = gym_model_env()

    def test_observations_are_in_the_space_with_the_named_keys(self):
        env = self.env
        self.assertEqual(list(env.observation_space.spaces), ['scan', 'odom', 'camera_small', 'joints'])
        self.assertEqual(env.observation_space['scan'].shape, (1081,))
        self.assertEqual(env.observation_space['camera_small'].shape, (84, 84, 3))
        self.assertEqual(env.observation_space['camera_small'].dtype, np.uint8)
        self.assertEqual(env.observation_space['joints'].shape, (3, 6))
        obs, info = env.reset(seed=3)
        self.assertTrue(env.observation_space.contains(obs), {k: v.dtype for k, v in obs.items()})
        for _ in range(30):
            obs, reward, terminated, truncated, info = env.step(np.array([1.0, 0.2], np.float32))
            self.assertTrue(env.observation_space.contains(obs))
        self.assertAlmostEqual(info['time'], 0.3, places=9)

    def test_action_space_is_the_drives_limits(self):
        space = self.env.action_space
        self.assertEqual(space.shape, (2,))
        self.assertEqual(float(space.high[0]), 3.0)  # the cmd_vel node's max_speed
        self.assertGreater(float(space.high[1]), 0.5)  # about 0.52 rad: inner wheel at 0.6
        self.assertLess(float(space.high[1]), 0.6)

    def test_only_the_observed_outputs_are_computed(self):
        samples = self.env.sim.sensor_samples()
        self.assertGreater(samples['hokuyo_sensor'], 0)
        self.assertGreater(samples['camera_small'], 0)
        self.assertEqual(samples['camera1'], 0)  # 800 x 800, not observed: never rendered
        self.assertEqual(samples['real_sense'], 0)

    def test_the_registered_id_passes_gymnasiums_checker(self):
        env = gym.make(tianracer_gym.ENV_ID, observe=('scan', 'odom'), max_episode_time=0.5)
        from gymnasium.utils.env_checker import check_env
        check_env(env.unwrapped, skip_render_check=True)
        env.close()


class DepthImage(unittest.TestCase):
    def test_no_return_is_nan_in_the_simulation_and_inf_in_the_env(self):
        """gazebo_ros_openni_kinect publishes NaN outside (pointCloudCutoff, pointCloudCutoffMax),
        for no return as for too near: Simulation's depth holds NaN there (never +-inf), as the ROS
        image does; the env's observation holds +inf in exactly those pixels (a Box cannot hold
        NaN), the same bits elsewhere (docs/learning.md)."""
        env = TianracerEnv(observe=('depth',), world='walled_room', reward=lambda *a: 0.0)
        try:
            env.reset(seed=0)
            obs, *_ = env.step(np.zeros(2))
            raw = env.sim.observation()['depth']
            self.assertEqual(raw.dtype, np.float32)
            self.assertGreater(np.isnan(raw).sum(), 0)  # the sky: no return
            self.assertGreater(np.isfinite(raw).sum(), 0)  # the floor and the walls
            self.assertFalse(np.isinf(raw).any())
            finite = raw[np.isfinite(raw)]
            self.assertGreater(finite.min(), 0.4)
            self.assertLess(finite.max(), 5.0)
            depth = obs['depth']
            self.assertFalse(np.isnan(depth).any())
            self.assertTrue(np.array_equal(np.isposinf(depth), np.isnan(raw)))
            self.assertFalse(np.isneginf(depth).any())
            self.assertTrue(np.array_equal(depth[np.isfinite(raw)].view(np.uint32),
                                           finite.view(np.uint32)))
            self.assertTrue(env.observation_space['depth'].contains(depth))
        finally:
            env.close()


class Determinism(unittest.TestCase):
    def test_reset_with_a_seed_repeats_and_another_seed_differs(self):
        env = gym_model_env()
        actions = [np.array([1.5, 0.3 * math.sin(k / 7.0)], np.float32) for k in range(40)]

        def run(seed):
            obs, _ = env.reset(seed=seed)
            out = [obs]
            for a in actions:
                out.append(env.step(a)[0])
            return out

        a, b, c = run(11), run(11), run(12)
        self.assertTrue(all(same(x, y) for x, y in zip(a, b)))
        self.assertFalse(same(a[0], c[0]))  # another start pose and noise
        self.assertFalse(same(a[-1], c[-1]))

    def test_reset_without_a_seed_starts_elsewhere(self):
        env = gym_model_env(observe=('odom',))
        first, _ = env.reset(seed=1)
        second, _ = env.reset()
        self.assertFalse(np.array_equal(first['odom'][:2], second['odom'][:2]))
        # ... on the centreline, facing along it, resting on the ground.
        s, lateral, _ = env.centreline.project(*second['odom'][:2])
        self.assertLess(abs(lateral), 1e-9)
        self.assertLess(abs(second['odom'][2] - 0.0095), 2e-3)

    def test_a_given_start_pose(self):
        env = gym_model_env(observe=('odom',))
        obs, _ = env.reset(seed=0, options={'pose': (1.0, 0.1, 0.2)})
        self.assertAlmostEqual(obs['odom'][0], 1.0, places=9)
        self.assertAlmostEqual(obs['odom'][1], 0.1, places=9)
        self.assertAlmostEqual(2 * math.atan2(obs['odom'][5], obs['odom'][6]), 0.2, places=9)


class Episodes(unittest.TestCase):
    def test_collision_terminates(self):
        # On the start straight facing the outer wall (y = -0.5) at full speed.
        env = gym_model_env(observe=('odom',))
        env.reset(seed=0, options={'pose': (0.0, 0.0, -math.pi / 2)})
        for k in range(300):
            _, _, terminated, truncated, info = env.step(np.array([2.0, 0.0], np.float32))
            if terminated:
                break
        self.assertTrue(terminated, 'no collision after %.2f s' % info['time'])
        self.assertTrue(info['collision'])
        self.assertFalse(truncated)
        self.assertLess(info['time'], 1.5)

    def test_time_limit_truncates_and_progress_is_the_reward(self):
        env = gym_model_env(observe=('odom',), max_episode_time=0.5, control_period=0.02)
        env.reset(seed=0, options={'pose': (0.0, 0.0, 0.0)})
        total, steps = 0.0, 0
        while True:
            _, reward, terminated, truncated, info = env.step(np.array([1.0, 0.0], np.float32))
            total += reward
            steps += 1
            if terminated or truncated:
                break
        self.assertTrue(truncated)
        self.assertFalse(terminated)
        self.assertEqual(steps, 25)
        self.assertAlmostEqual(total, info['progress'], places=12)
        self.assertGreater(total, 0.25)  # about 0.4 m at 1 m/s after the start
        self.assertLess(total, 0.5)

    def test_raw_controller_commands(self):
        env = gym_model_env(observe=('odom', 'joints'), action='commands')
        names = [c['controller'] for c in env.sim.commands]
        env.reset(seed=0, options={'pose': (0.0, 0.0, 0.0)})
        a = np.zeros(len(names), np.float32)
        for i, n in enumerate(names):
            if 'rear_wheel' in n:
                a[i] = 1.0 / 0.032  # 1 m/s
        for _ in range(100):
            obs = env.step(a)[0]
        self.assertGreater(obs['odom'][0], 0.5)
        self.assertLess(abs(obs['odom'][1]), 0.05)

    def test_a_callable_reward(self):
        env = gym_model_env(observe=('odom',), reward=lambda env, obs, info: -obs['odom'][0])
        env.reset(seed=0, options={'pose': (0.0, 0.0, 0.0)})
        obs, reward, *_ = env.step(np.array([1.0, 0.0], np.float32))
        self.assertEqual(reward, -obs['odom'][0])


class BadInput(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.env = gym_model_env(observe=('odom',))
        cls.env.reset(seed=0)

    def error(self, f):
        with self.assertRaises(ValueError) as c:
            f()
        return str(c.exception)

    def test_non_utf8_text_reaches_python_intact(self):
        # Names and values are quoted from the user's files, which need not be UTF-8 (issue 43:
        # the InputError arrived empty and drain_warnings() raised UnicodeDecodeError).
        import tempfile
        from tianracer_sim import simulator
        inertia = b'<inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        with tempfile.TemporaryDirectory() as d:
            bad = os.path.join(d, 'bad.urdf')
            with open(bad, 'wb') as f:
                f.write(b'<robot name="c"><link name="caf\xe9"><inertial><mass value="-1"/>' +
                        inertia + b'</inertial></link></robot>')
            msg = self.error(lambda: simulator.Simulation(model=bad, world='empty'))
            self.assertIn("link 'caf\\xe9': mass '-1' must be a positive finite number", msg)
            warn = os.path.join(d, 'warn.urdf')
            with open(warn, 'wb') as f:
                f.write(b'<robot name="c"><link name="base"><inertial><mass value="1"/>' + inertia +
                        b'</inertial></link><gazebo reference="caf\xe9"><mu1>1</mu1></gazebo></robot>')
            simulator.drain_warnings()
            simulator.Simulation(model=warn, world='empty')
            warnings = simulator.drain_warnings()
            self.assertTrue(any("no link named 'caf\\xe9'" in w for w in warnings), warnings)

    def test_an_action_outside_the_space(self):
        msg = self.error(lambda: self.env.step(np.array([5.0, 0.0], np.float32)))
        self.assertIn('outside the action space', msg)
        self.assertIn('5.0', msg)

    def test_nan_and_a_wrong_shape(self):
        self.assertIn('is not finite', self.error(lambda: self.env.step(np.array([np.nan, 0.0]))))
        self.assertIn('shape', self.error(lambda: self.env.step(np.array([1.0, 0.0, 0.0]))))

    def test_a_model_with_no_such_sensor(self):
        msg = self.error(lambda: gym_model_env(observe=('odom', 'lidar_front')))
        self.assertIn("observation 'lidar_front': the model has no such sensor", msg)
        self.assertIn('hokuyo_sensor (lidar)', msg)
        msg = self.error(lambda: gym_model_env(observe=('imu',)))
        self.assertIn("observation 'imu': the model has no such sensor", msg)
        msg = self.error(lambda: gym_model_env(observe=('image',)))  # camera1 and camera_small
        self.assertIn('several (camera1, camera_small): name one', msg)
        msg = self.error(lambda: gym_model_env(observe=('real_sense/points',)))
        self.assertIn("has no output 'points'; it has depth, image", msg)

    def test_an_unknown_world(self):
        msg = self.error(lambda: gym_model_env(world='moon_base'))
        self.assertIn("world 'moon_base' is neither a shipped world", msg)

    def test_a_wrong_control_period(self):
        for period in (0.0105, 0.0, -0.01, 0.0004, float('nan')):
            msg = self.error(lambda: gym_model_env(control_period=period))
            self.assertIn('is not a positive multiple of the physics step 0.001 s', msg)

    def test_progress_without_a_centreline(self):
        msg = self.error(lambda: gym_model_env(world='empty'))
        self.assertIn("reward='progress' needs a centreline", msg)

    def test_ackermann_on_a_model_without_its_controllers(self):
        msg = self.error(lambda: TianracerEnv(model=packages.default_model(), world='empty',
                                              reward=lambda *a: 0.0, observe=('odom',)))
        self.assertIn('no Ackermann drive', msg)
        self.assertIn("use action='commands'", msg)

    def test_a_bad_controller_yaml(self):
        import tempfile
        with tempfile.NamedTemporaryFile('w', suffix='.yaml') as f:
            f.write('tianracer:\n  c:\n    type: velocity_controllers/JointVelocityController\n'
                    '    joint: [1, 2]\n')
            f.flush()
            msg = self.error(lambda: gym_model_env(control_config=f.name))
        self.assertIn("controller 'c': joint must be a string, got a list", msg)
        self.assertTrue(msg.startswith(f.name + ':3: '), msg)  # the file, the controller's line


if __name__ == '__main__':
    unittest.main()
