"""TianracerVectorEnv: N TianracerEnvs in one process, stepped together on C++ threads with the
GIL released (tianracer_sim.simulator.SimulationBatch), with the gymnasium.vector API and
autoreset (NEXT_STEP: the step after an episode ends resets that env and ignores its action).

Each env i is exactly the single TianracerEnv with the same arguments and reset seed seed + i:
same observations, rewards and ends, bit for bit.
"""
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from tianracer_sim import simulator

from .env import TianracerEnv


class TianracerVectorEnv(VectorEnv):
    metadata = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(self, num_envs, threads=0, copy_observations=True, **env_kwargs):
        if int(num_envs) < 1:
            raise ValueError("num_envs must be >= 1, got %r" % (num_envs,))
        self.num_envs = int(num_envs)
        first = TianracerEnv(**env_kwargs)
        # The others from the first one's URDF: xacro runs once.
        same = dict(env_kwargs, urdf=first.sim.urdf, model=None, model_args=(),
                    model_dir=first.model_dir, control_config=first.control_config)
        self.envs = [first] + [TianracerEnv(**same) for _ in range(self.num_envs - 1)]
        self.batch = simulator.SimulationBatch([e.sim for e in self.envs], threads)
        self.single_observation_space = first.observation_space
        self.single_action_space = first.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        self.copy_observations = copy_observations
        self._obs = {key: np.zeros((self.num_envs,) + tuple(shape), dtype=np.dtype(dtype))
                     for key, shape, dtype in first.sim.observation_specs}
        self._contacts = np.zeros(self.num_envs, dtype=np.int64)
        self._autoreset = np.zeros(self.num_envs, dtype=bool)
        self._rewards = np.zeros(self.num_envs, dtype=np.float64)
        self._terminated = np.zeros(self.num_envs, dtype=bool)
        self._truncated = np.zeros(self.num_envs, dtype=bool)

    @property
    def threads(self):
        return self.batch.threads

    def _row(self, i):
        return {k: v[i] for k, v in self._obs.items()}

    def _result_obs(self):
        # A dict of arrays: copying each array is what deepcopy does, without its machinery.
        return {k: v.copy() for k, v in self._obs.items()} if self.copy_observations else self._obs

    def reset(self, *, seed=None, options=None):
        if seed is None:
            seeds = [None] * self.num_envs
        elif isinstance(seed, int):
            seeds = [seed + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError("reset: %d seeds for %d envs" % (len(seeds), self.num_envs))
        self._np_random_seed = seeds[0] if seed is not None else None
        infos = {}
        for i, env in enumerate(self.envs):
            _, info = env.reset(seed=seeds[i], options=options)
            self.batch.read(i, self._obs)
            env._fix(self._row(i))
            infos = self._add_info(infos, info, i)
        self._autoreset[:] = False
        return self._result_obs(), infos

    def step(self, actions):
        actions = np.asarray(actions)
        if actions.shape != self.action_space.shape:
            raise ValueError("actions have shape %s; the action space is %s" %
                             (actions.shape, self.action_space))
        active = ~self._autoreset
        # Every env has the same action space: all rows at once; the first bad one raises its
        # env's message (TianracerEnv._checked).
        rows = np.asarray(actions, dtype=np.float64)
        ok = self.envs[0]._within_bounds(rows)
        if not ok[active].all():
            for i in np.flatnonzero(active & ~ok):
                self.envs[i]._checked(actions[i])
        rows = np.where(active[:, None], rows, 0.0)
        infos = [None] * self.num_envs
        # Envs whose episode ended at the last step start a new one (their action is ignored).
        for i in np.flatnonzero(~active):
            _, info = self.envs[i].reset()
            self.batch.read(i, self._obs)
            self.envs[i]._fix(self._row(i))
            infos[i] = info
        self._contacts[:] = 0
        if active.any():
            self.batch.step(rows, self.envs[0].action_mode, self.envs[0].steps_per_action,
                            self._obs, active, self._contacts)
        self._rewards[:] = 0.0
        self._terminated[:] = False
        self._truncated[:] = False
        for i in np.flatnonzero(active):
            env = self.envs[i]
            obs = self._row(i)
            env._fix(obs)
            _, reward, terminated, truncated, info = env._outcome(obs, int(self._contacts[i]))
            self._rewards[i] = reward
            self._terminated[i] = terminated
            self._truncated[i] = truncated
            infos[i] = info
        self._autoreset = self._terminated | self._truncated
        return (self._result_obs(), self._rewards.copy(), self._terminated.copy(),
                self._truncated.copy(), self._batched_infos(infos))

    def _batched_infos(self, infos):
        """What VectorEnv._add_info makes of the envs' infos (one per env, in order), built in one
        go when they are what the env gives (the same keys, each a float or a bool of one type
        across the envs); anything else (a reward callable may add to info) through _add_info."""
        first = infos[0]
        out = {}
        for key, value in first.items():
            kind = type(value)
            if kind not in (float, bool) or key == "final_obs":
                break
            values = [info.get(key) for info in infos]
            if any(type(v) is not kind for v in values):
                break
            out[key] = np.array(values, dtype=kind)
            out["_" + key] = np.ones(self.num_envs, dtype=np.bool_)
        else:
            if all(len(info) == len(first) for info in infos):
                return out
        out = {}
        for i, info in enumerate(infos):
            out = self._add_info(out, info, i)
        return out

    def close_extras(self, **kwargs):
        self.batch = None
        self.envs = []
