#!/usr/bin/env python3
"""Random actions in tianracer_gym: prints the observation and action spaces and the time of one
env step (CPU time of this process, and wall time).

    source .build/devel/setup.bash
    python3 examples/gym_random.py [--steps 1000] [--observe scan odom]
"""
import argparse
import time

import gymnasium as gym
import numpy as np

import tianracer_gym


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--steps', type=int, default=1000)
    p.add_argument('--observe', nargs='+', default=['scan', 'odom'])
    p.add_argument('--world', default='racetrack')
    p.add_argument('--seed', type=int, default=0)
    args = p.parse_args()

    env = gym.make(tianracer_gym.ENV_ID, observe=tuple(args.observe), world=args.world)
    print('observation space:')
    for key, space in env.observation_space.spaces.items():
        print('  %-14s %s' % (key, space))
    print('action space:      %s  (speed m/s, steering angle rad)' % env.action_space)
    print('control period:    %g s (%d physics steps of %g s)' % (
        env.unwrapped.control_period, env.unwrapped.steps_per_action, env.unwrapped.sim.dt))

    env.action_space.seed(args.seed)
    obs, info = env.reset(seed=args.seed)
    episodes, cpu0, wall0 = 1, time.process_time(), time.perf_counter()
    for _ in range(args.steps):
        obs, reward, terminated, truncated, info = env.step(env.action_space.sample())
        if terminated or truncated:
            obs, info = env.reset()
            episodes += 1
    cpu, wall = time.process_time() - cpu0, time.perf_counter() - wall0
    print('%d steps, %d episodes, sim time %.2f s at the end' % (args.steps, episodes, info['time']))
    print('per env step: %.0f us CPU, %.0f us wall (%.0f env-steps/s by CPU time)' % (
        cpu / args.steps * 1e6, wall / args.steps * 1e6, args.steps / cpu))
    for key, value in obs.items():
        print('  last %-12s shape %s dtype %s, e.g. %s' % (key, value.shape, value.dtype,
                                                            np.array2string(value.ravel()[:4], precision=3)))
    env.close()


if __name__ == '__main__':
    main()
