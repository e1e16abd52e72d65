"""TianracerVectorEnv: the same results as N single envs (bit for bit, autoreset included), the
gymnasium.vector API, and the threads."""
import unittest

import os
import sys

# catkin runs nosetests with -P (no path adjustment): the test folder's helpers by path.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import support  # noqa: F401  (ROS_PACKAGE_PATH)

import gymnasium as gym
import numpy as np

import tianracer_gym
from tianracer_gym import TianracerEnv, TianracerVectorEnv, packages

N = 3
KWARGS = dict(model=packages.gym_model(), control_config=packages.default_control_config(),
              observe=('scan', 'odom', 'camera_small'), max_episode_time=0.3,
              control_period=0.02)


def actions(k):
    """Actions of step k for env i: different per env, some wall hits at full lock."""
    return np.array([[2.5, 0.5 * np.sin(0.3 * k + i)] for i in range(N)], np.float32)


class BatchedInfos(unittest.TestCase):
    """The vector env builds its infos in one go; they are what gymnasium's _add_info makes."""

    @classmethod
    def setUpClass(cls):
        cls.vec = TianracerVectorEnv(N, threads=1, **KWARGS)

    @classmethod
    def tearDownClass(cls):
        cls.vec.close()

    def expected(self, infos):
        out = {}
        for i, info in enumerate(infos):
            out = gym.vector.VectorEnv._add_info(self.vec, out, info, i)
        return out

    def same(self, got, want):
        self.assertEqual(list(got), list(want))
        for key in want:
            if isinstance(want[key], dict):
                self.same(got[key], want[key])
                continue
            self.assertEqual(got[key].dtype, want[key].dtype, key)
            self.assertEqual(got[key].tolist(), want[key].tolist(), key)

    def check(self, infos):
        self.same(self.vec._batched_infos(infos), self.expected(infos))

    def test_the_envs_infos(self):
        self.check([{'time': 0.01 * i, 'progress': 0.5 + i, 'collision': i == 1} for i in range(N)])

    def test_other_infos_take_add_info(self):
        base = [{'time': 0.01, 'progress': 0.5, 'collision': False} for _ in range(N)]
        extra = [dict(b) for b in base]
        extra[1]['lap'] = 2  # a reward callable added a key to one env's info
        self.check(extra)
        mixed = [dict(b) for b in base]
        mixed[2]['progress'] = np.float64(0.25)  # another type in one env
        self.check(mixed)
        nested = [dict(b, detail={'a': 1.0}) for b in base]
        self.check(nested)


class VectorEqualsSingles(unittest.TestCase):
    def test_same_results_as_n_single_envs_with_autoreset(self):
        vec = TianracerVectorEnv(N, threads=2, **KWARGS)
        self.assertEqual(vec.threads, 2)
        singles = [TianracerEnv(**KWARGS) for _ in range(N)]
        obs, _ = vec.reset(seed=100)
        single_obs = [e.reset(seed=100 + i)[0] for i, e in enumerate(singles)]
        self.assertTrue(vec.observation_space.contains(obs))
        for i in range(N):
            for key in obs:
                self.assertEqual(obs[key][i].tobytes(), single_obs[i][key].tobytes(), key)
        resets = 0
        pending = [False] * N  # NEXT_STEP autoreset: the step after an end resets
        for k in range(40):
            a = actions(k)
            obs, rewards, terminated, truncated, infos = vec.step(a)
            for i, env in enumerate(singles):
                if pending[i]:
                    o, info = env.reset()
                    r, te, tr = 0.0, False, False
                    resets += 1
                else:
                    o, r, te, tr, info = env.step(a[i])
                pending[i] = te or tr
                for key, value in info.items():  # the info too, as gymnasium batches it
                    self.assertEqual(infos[key][i], value, 'step %d env %d info %s' % (k, i, key))
                    self.assertEqual(infos[key].dtype, np.dtype(type(value)), key)
                    self.assertTrue(infos['_' + key][i], key)
                for key in o:
                    self.assertEqual(obs[key][i].tobytes(), o[key].tobytes(),
                                     'step %d env %d %s' % (k, i, key))
                self.assertEqual(rewards[i], r)
                self.assertEqual(terminated[i], te)
                self.assertEqual(truncated[i], tr)
        self.assertGreaterEqual(resets, N)  # every env went through an autoreset
        vec.close()

    def test_make_vec_gives_the_threaded_vector_env(self):
        envs = gym.make_vec(tianracer_gym.ENV_ID, num_envs=2, observe=('odom',))
        self.assertIsInstance(envs.unwrapped, TianracerVectorEnv)
        obs, infos = envs.reset(seed=0)
        self.assertEqual(obs['odom'].shape, (2, 13))
        obs, rewards, terminated, truncated, infos = envs.step(envs.action_space.sample())
        self.assertEqual(rewards.shape, (2,))
        self.assertIn('progress', infos)
        envs.close()

    def test_bad_actions_are_refused_before_any_env_steps(self):
        vec = TianracerVectorEnv(2, observe=('odom',))
        vec.reset(seed=0)
        t = [e.sim.time for e in vec.envs]
        with self.assertRaises(ValueError) as c:
            vec.step(np.array([[1.0, 0.0], [9.0, 0.0]], np.float32))
        self.assertIn('outside the action space', str(c.exception))
        self.assertEqual([e.sim.time for e in vec.envs], t)


if __name__ == '__main__':
    unittest.main()
