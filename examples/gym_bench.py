#!/usr/bin/env python3
"""Env-steps per second of tianracer_gym at a 0.01 s control period (10 physics steps of 1 ms),
measured by CPU time (this process and its threads: time.process_time), so that other work on a
shared machine does not count; wall-clock figures are printed too.

    source .build/devel/setup.bash
    python3 examples/gym_bench.py [--steps 3000] [--out bench.md]

Rows: one env with the state only (odom), with the 1081-beam lidar, with the lidar and an
84 x 84 camera (tianracer_gym/models/tianracer_gym.xacro); then vector envs of 2, 4 and 8 (lidar)
on C++ threads. The split of one env step: physics (controllers, Bullet, contacts: CPU of the
stepping thread), sensors (casting and rendering requests on the stepping thread, plus the frame
worker's rendering), Python (the rest: the env, numpy, bindings). Memory: resident set size per
env, from a vector env of 8. The last line is the one env with the lidar by CPU time:
`1 env + lidar: N env-steps/s`.
"""
import argparse
import os
import time

import numpy as np

from tianracer_gym import TianracerEnv, TianracerVectorEnv, packages

PERIOD = 0.01


def rss_mb():
    with open('/proc/self/status') as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024.0
    return float('nan')


def actions(k, n=None):
    a = np.array([1.2, 0.3 * np.sin(k / 50.0)], np.float32)
    return a if n is None else np.tile(a, (n, 1))


def single(label, steps, **kwargs):
    env = TianracerEnv(control_period=PERIOD, max_episode_time=1e9, timing=True,
                       terminate_on_collision=False, random_start=False, **kwargs)
    env.reset(seed=0, options={'pose': (0.0, 0.0, 0.0)})
    for k in range(50):  # warm up (first frames, caches)
        env.step(actions(k))
    env.reset(seed=0, options={'pose': (0.0, 0.0, 0.0)})
    env.sim.clear_timing()
    cpu0, thread0, wall0 = time.process_time(), time.thread_time(), time.perf_counter()
    for k in range(steps):
        env.step(actions(k))
        if k % 1500 == 1499:  # 15 s of sim time: back to the start before the walls
            env.sim.reset(pose=[0.0, 0.0, 0.0])
    cpu = time.process_time() - cpu0
    others = cpu - (time.thread_time() - thread0)  # frame worker, Embree, llvmpipe threads
    wall = time.perf_counter() - wall0
    t = env.sim.timing()
    physics = t['physics'] / steps
    sensors = t['sensors'] / steps + others / steps
    python = cpu / steps - physics - sensors
    return dict(label=label, n=1, cpu_rate=steps / cpu, wall_rate=steps / wall, step_us=cpu / steps * 1e6,
                physics_us=physics * 1e6, sensors_us=sensors * 1e6, python_us=python * 1e6)


def vector(n, steps, **kwargs):
    rss0 = rss_mb()
    envs = TianracerVectorEnv(n, control_period=PERIOD, max_episode_time=1e9, timing=True,
                              terminate_on_collision=False, random_start=False, **kwargs)
    mem = (rss_mb() - rss0) / n
    envs.reset(seed=0, options={'pose': (0.0, 0.0, 0.0)})
    for k in range(20):
        envs.step(actions(k, n))
    for e in envs.envs:
        e.sim.clear_timing()
    cpu0, wall0 = time.process_time(), time.perf_counter()
    for k in range(steps):
        envs.step(actions(k, n))
        if k % 1500 == 1499:
            for e in envs.envs:
                e.sim.reset(pose=[0.0, 0.0, 0.0])
    cpu = time.process_time() - cpu0
    wall = time.perf_counter() - wall0
    work = sum(e.sim.timing()['physics'] + e.sim.timing()['sensors'] for e in envs.envs)
    serial = cpu - work  # the Python side and the copies, with the GIL held
    threads = envs.threads
    envs.close()
    total = steps * n
    # On `threads` free cores: serial + work / threads per step (Amdahl), against all on one.
    est = (serial + work) / (serial + work / min(threads, os.cpu_count()))
    return dict(label='vector env of %d (%d threads)' % (n, threads), n=n, cpu_rate=total / cpu,
                wall_rate=total / wall, step_us=cpu / total * 1e6, speedup=est, mem=mem,
                serial_us=serial / total * 1e6)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--steps', type=int, default=3000, help='env steps per row (per env for vectors)')
    p.add_argument('--quick', action='store_true', help='1 and 2 envs only (a smoke test)')
    p.add_argument('--out', help='also write the table (markdown) here')
    args = p.parse_args()
    scan = dict(observe=('scan', 'odom'))
    rows = [single('1 env, state only', args.steps, observe=('odom',)),
            single('1 env + lidar (1081 beams, 40 Hz)', args.steps, **scan),
            single('1 env + lidar + 84x84 camera (30 Hz)', args.steps, model=packages.gym_model(),
                   control_config=packages.default_control_config(),
                   observe=('scan', 'odom', 'camera_small'))]
    for n in ((2,) if args.quick else (2, 4, 8)):
        rows.append(vector(n, max(1, args.steps // n), **scan))

    lines = ['| configuration | env-steps/s (CPU time) | env-steps/s (wall) | one env step: CPU us '
             '| physics / sensors / Python us | est. speed-up on the cores | memory per env |',
             '|---|---|---|---|---|---|---|']
    for r in rows:
        split = ('%.0f / %.0f / %.0f' % (r['physics_us'], r['sensors_us'], r['python_us'])
                 if 'physics_us' in r else 'serial (GIL) %.0f' % r['serial_us'])
        lines.append('| %s | %.0f | %.0f | %.0f | %s | %s | %s |' % (
            r['label'], r['cpu_rate'], r['wall_rate'], r['step_us'], split,
            '%.2fx' % r['speedup'] if 'speedup' in r else '', '%.0f MB' % r['mem'] if 'mem' in r else ''))
    table = '\n'.join(lines)
    print(table)
    print('\n%d cores, load average %s; physics step %g s, control period %g s' % (
        os.cpu_count(), ' '.join('%.1f' % v for v in os.getloadavg()), 0.001, PERIOD))
    if args.out:
        with open(args.out, 'w') as f:
            f.write(table + '\n')
    # Last, the figure SPEC 9's goal is about (>= 3,000 on one core), by CPU time.
    print('1 env + lidar: %d env-steps/s' % round(rows[1]['cpu_rate']))


if __name__ == '__main__':
    main()
