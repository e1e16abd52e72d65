"""Gymnasium environments of tianracer sim (docs/learning.md).

    import gymnasium as gym
    import tianracer_gym  # registers the ids
    env = gym.make("tianracer_gym/Tianracer-v0", observe=("scan", "odom"))
    envs = gym.make_vec("tianracer_gym/Tianracer-v0", num_envs=4)  # C++ threads, one process
"""
import gymnasium

from .env import TianracerEnv, observation_space_of  # noqa: F401
from .vector import TianracerVectorEnv  # noqa: F401

ENV_ID = "tianracer_gym/Tianracer-v0"

if ENV_ID not in gymnasium.registry:
    gymnasium.register(id=ENV_ID, entry_point="tianracer_gym.env:TianracerEnv",
                       vector_entry_point="tianracer_gym.vector:TianracerVectorEnv",
                       disable_env_checker=False)
